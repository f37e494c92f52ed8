/* semnav: semantic navigation from tilting-laser sweeps */
// WaypointBuilder: line-of-sight thinning of a CNN path on an L-shaped
// corridor, and the waypoint sequence handed to MRPT.
#include <gtest/gtest.h>
#include <semnav/nav/WaypointBuilder.h>
#include <semnav/planning/CnnPlanner.h>
#include <semnav/planning/GoalLayer.h>

#include <cmath>

using namespace semnav;

namespace
{
/** 6 m x 6 m at 5 cm, free only in an L: x in [0.5, 1.5] (going north) and
 * y in [4.5, 5.5] (going east). */
TraversabilityGrid corridorL()
{
	const GridGeometry g(0.05, 0, 0, 120, 120);
	TraversabilityGrid u(g, 1e6, 1e6);
	for (int r = 0; r < g.rows; r++)
		for (int c = 0; c < g.cols; c++)
		{
			const double x = g.centerX(c), y = g.centerY(r);
			const bool free = (x > 0.5 && x < 1.5 && y > 0.5 && y < 5.5) ||
			                  (y > 4.5 && y < 5.5 && x > 0.5 && x < 5.5);
			u.setU(r, c, free ? 0.0 : 1e6);
		}
	return u;
}
}  // namespace

TEST(WaypointBuilder, ThinnedPathKeepsLineOfSightAndEnds)
{
	const TraversabilityGrid u = corridorL();
	GoalLayer goals(u.geometry());
	goals.addDisc(5.0, 5.0, 0.2);
	const PlannedPath path = CnnPlanner().plan(u, goals, 1.0, 1.0);
	ASSERT_GT(path.points.size(), 50u);
	const double spacing = 1.5;
	const auto w = WaypointBuilder::thin(path, u, spacing);
	// Far fewer points, same ends, every leg visible and short enough.
	EXPECT_LT(w.size(), path.points.size() / 5);
	EXPECT_GE(w.size(), 4u);  // the corner needs a waypoint
	EXPECT_EQ(w.front().x, path.points.front().x);
	EXPECT_EQ(w.back().y, path.points.back().y);
	for (std::size_t i = 1; i < w.size(); i++)
	{
		EXPECT_TRUE(WaypointBuilder::lineOfSight(u, w[i - 1], w[i], 0.0));
		EXPECT_LE(
		    std::hypot(w[i].x - w[i - 1].x, w[i].y - w[i - 1].y),
		    spacing + 1e-9);
	}
	// A leg across the corner would leave the corridor.
	EXPECT_FALSE(WaypointBuilder::lineOfSight(u, w.front(), w.back(), 0.0));
}

TEST(WaypointBuilder, LineOfSightRespectsCostlierCells)
{
	TraversabilityGrid u = corridorL();
	const GridGeometry& g = u.geometry();
	// A costly patch in the vertical corridor.
	for (int r = 40; r < 50; r++)
		for (int c = 10; c < 30; c++) u.setU(r, c, 2.0);
	EXPECT_FALSE(WaypointBuilder::lineOfSight(u, {1.0, 1.0}, {1.0, 4.0}, 0.0));
	EXPECT_TRUE(WaypointBuilder::lineOfSight(u, {1.0, 1.0}, {1.0, 4.0}, 2.0));
	EXPECT_FALSE(WaypointBuilder::lineOfSight(u, {1.0, 1.0}, {-1.0, 1.0}, 10.0))
	    << "leaving the grid is not a line of sight";
	(void)g;
}

TEST(WaypointBuilder, SequenceForADifferentialDrive)
{
	const std::vector<mrpt::math::TPoint2D> pts{{0, 0}, {1, 0}, {2, 1}, {3, 1}};
	const auto seq = WaypointBuilder::toSequence(pts, 0.35, 0.15);
	ASSERT_EQ(seq.waypoints.size(), 3u);  // the start is where the robot is
	for (std::size_t i = 0; i < 3; i++)
	{
		const auto& wp = seq.waypoints[i];
		EXPECT_TRUE(wp.isValid());
		EXPECT_FALSE(wp.target_heading.has_value());
		EXPECT_EQ(wp.allow_skip, i < 2);
		EXPECT_DOUBLE_EQ(wp.allowed_distance, i < 2 ? 0.35 : 0.15);
		EXPECT_DOUBLE_EQ(wp.target.x, pts[i + 1].x);
	}
}
