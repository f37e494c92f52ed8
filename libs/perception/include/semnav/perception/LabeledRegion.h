/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/math/TPoint3D.h>
#include <semnav/common/Label.h>

#include <cstddef>
#include <opencv2/core/types.hpp>

namespace semnav
{
/** One classified region of a sweep: a connected set of pixels with one
 * label (a surface split off a segmentation area, or the merged floor /
 * sidewalk / grass). Points and normals in the robot frame. */
struct LabeledRegion
{
	/** Index in LabeledSweep::regions and value in LabeledSweep::regionIds. */
	int id = -1;
	Label label = Label::Unknown;
	/** Segmentation area of its first pixel in row-major order (0 = none). */
	int area = 0;
	std::size_t pixels = 0;
	/** Bounding box in the sweep image (x = column, y = row). */
	cv::Rect imageBox;
	mrpt::math::TPoint3D centroid{0, 0, 0};
	/** Axis-aligned bounding box of its points (robot frame). */
	mrpt::math::TPoint3D minCorner{0, 0, 0}, maxCorner{0, 0, 0};
	/** Horizontal extent along the surface (vertical surfaces: along the
	 * wall; others: the larger horizontal bounding-box side), m. */
	double width = 0;
	/** Vertical extent (max z - min z), m. */
	double height = 0;
	/** Mean of its pixels' unit normals, renormalised; (0,0,0) if none. */
	mrpt::math::TPoint3D meanNormal{0, 0, 0};
	/** Mean R-bar of its pixels (NaN when no pixel has one). */
	double meanRoughness = 0;
};

}  // namespace semnav
