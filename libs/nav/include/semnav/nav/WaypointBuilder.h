/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/math/TPoint2D.h>
#include <mrpt/nav/reactive/TWaypoint.h>
#include <semnav/planning/PlannedPath.h>
#include <semnav/planning/TraversabilityGrid.h>

#include <vector>

namespace semnav
{
/** Turns a CNN path (a chain of cells) into waypoints for MRPT's
 * CWaypointsNavigator: the path is thinned by line of sight on the
 * traversability grid (a waypoint is dropped when the straight segment
 * that replaces it crosses no blocked cell and no cell costlier than the
 * costliest cell of the path it replaces), with a maximum spacing so the
 * reactive navigator always has a waypoint within its PTG range. */
class WaypointBuilder
{
public:
	/** Thinned points, first = path start, last = path end (goal). */
	static std::vector<mrpt::math::TPoint2D> thin(
	    const PlannedPath& path, const TraversabilityGrid& u,
	    double maxSpacing);

	/** True when the segment a-b crosses no cell with u > maxU (nor a
	 * blocked cell, nor leaves the grid). */
	static bool lineOfSight(
	    const TraversabilityGrid& u, const mrpt::math::TPoint2D& a,
	    const mrpt::math::TPoint2D& b, double maxU);

	/** Waypoints for the points after the first (the robot stands on it):
	 * intermediate ones with `allowedDistance` and allow_skip, the last
	 * one (the goal) with `finalAllowedDistance` and no skip; no
	 * target_heading (a differential drive turns on the way). */
	static mrpt::nav::TWaypointSequence toSequence(
	    const std::vector<mrpt::math::TPoint2D>& points, double allowedDistance,
	    double finalAllowedDistance);
};

}  // namespace semnav
