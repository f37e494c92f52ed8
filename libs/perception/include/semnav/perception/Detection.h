/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/math/TPoint3D.h>
#include <semnav/common/Label.h>

#include <opencv2/core/types.hpp>

namespace semnav
{
/** An object found in a sweep image by a detector (the Haar cascade stage
 * of sec. 2.2.2 fills these; the rule classifier leaves the list empty). */
struct Detection
{
	Label label = Label::Unknown;
	/** Bounding box in the sweep image (x = column, y = row). */
	cv::Rect imageBox;
	/** Robot-frame centroid and size of the object's points. */
	mrpt::math::TPoint3D centroid{0, 0, 0};
	mrpt::math::TPoint3D extent{0, 0, 0};
	/** Detector confidence (larger = surer). */
	double score = 0;
	/** The class's 3D shape check score in [0, 1] (1 when the class has
	 * no shape model). */
	double shapeScore = 1;
};

}  // namespace semnav
