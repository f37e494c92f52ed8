/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <opencv2/core/types.hpp>
#include <optional>
#include <vector>

namespace semnav
{
/** The wall behind an object, in the top view of a detection's points: a
 * straight line that the sensor (the origin) sees everything else in front
 * of and that reaches past the rest on the sides. Washbasins and stairs
 * stand against walls; beside the robot a wall is seen over a few rows only
 * and the rule classifier leaves it to objects, so a detection's points
 * hold the object and a slab of its wall (the shape check then scores a
 * wall, not the object). CascadeDetector::measure cuts it off
 * (back_wall_length_m). A stair's top riser has the lower steps in
 * front of it but does not reach past them, a box's front face has nothing
 * in front: neither is a back wall. */
class BackWall
{
public:
	struct Params
	{
		/** Shortest wall (m, along the line, 5th to 95th percentile). */
		double minLength = 0.8;
		/** Points this close to the line are on the wall (m). */
		double tolerance = 0.04;
		/** How far the wall reaches past the points in front of it, both
		 * sides together (m). */
		double minOverhang = 0.15;
		/** At most this fraction of all points behind the wall. */
		double maxBehind = 0.05;
		/** At least this fraction of all points in front of it. */
		double minInFront = 0.2;
		/** Line hypotheses (pairs of points, a fixed seeded draw). */
		int hypotheses = 64;
	};
	/** A line n . p = offset (unit n, offset > 0: the sensor is on the
	 * side n . p < offset). */
	struct Line
	{
		cv::Point2d normal;
		double offset = 0;
		/** Signed distance: < 0 in front (the sensor's side), > 0 behind. */
		double distance(const cv::Point2d& p) const
		{
			return normal.dot(p) - offset;
		}
	};

	/** The back wall of `xy` (robot frame, m), if there is one. The same
	 * points in the same order give the same line. */
	static std::optional<Line> find(
	    const std::vector<cv::Point2d>& xy, const Params& params);
};

}  // namespace semnav
