/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/math/TPoint3D.h>
#include <semnav/common/Label.h>

#include <cstddef>

namespace semnav
{
/** One object of the semantic map (a washbasin, a door...), merged from the
 * detections of several sweeps. World frame, metres. */
struct ObjectInstance
{
	/** 1-based id, also the value of the map's "objects" layer. */
	int id = 0;
	Label label = Label::Unknown;
	/** Mean of the detections' centroids. */
	mrpt::math::TPoint3D centroid{0, 0, 0};
	/** Axis-aligned bounds of all detections. */
	mrpt::math::TPoint3D minCorner{0, 0, 0}, maxCorner{0, 0, 0};
	/** Sweeps in which the object was detected. */
	std::size_t observations = 0;
	/** Sweeps that had it in view (line of sight to its centroid within
	 * the sweep's field of view and range), detected or not. */
	std::size_t views = 0;

	mrpt::math::TPoint3D extent() const
	{
		return {
		    maxCorner.x - minCorner.x, maxCorner.y - minCorner.y,
		    maxCorner.z - minCorner.z};
	}
};

}  // namespace semnav
