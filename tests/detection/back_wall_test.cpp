/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <semnav/detection/BackWall.h>

#include <cmath>

using namespace semnav;

namespace
{
/** Points along the segment a..b, `n` of them. */
void addSegment(
    std::vector<cv::Point2d>& out, cv::Point2d a, cv::Point2d b, int n)
{
	for (int i = 0; i < n; i++) out.push_back(a + (b - a) * (i / (n - 1.0)));
}
}  // namespace

TEST(BackWall, FindsTheWallBehindAnObject)
{
	// A wall 3 m ahead, 1.6 m long; a round object 0.4 m across in front.
	std::vector<cv::Point2d> xy;
	addSegment(xy, {3.0, -0.8}, {3.0, 0.8}, 160);
	for (int i = 0; i <= 40; i++)
	{
		const double a = M_PI / 2 + M_PI * i / 40.0;
		xy.emplace_back(2.75 + 0.2 * std::cos(a), 0.2 * std::sin(a));
	}
	const auto wall = BackWall::find(xy, {});
	ASSERT_TRUE(wall.has_value());
	EXPECT_NEAR(std::abs(wall->normal.x), 1.0, 1e-3);
	EXPECT_NEAR(wall->offset, 3.0, 0.01);
	EXPECT_LT(wall->distance({2.6, 0.0}), -0.3);
	// Along the line of sight (a wall the object stands against, seen
	// grazing): the same.
	std::vector<cv::Point2d> side;
	addSegment(side, {1.0, 1.0}, {2.5, 1.0}, 150);
	addSegment(side, {1.5, 0.7}, {1.9, 0.7}, 60);
	const auto grazing = BackWall::find(side, {});
	ASSERT_TRUE(grazing.has_value());
	EXPECT_NEAR(grazing->offset, 1.0, 0.01);
}

TEST(BackWall, NoWallBehindConvexObjectsStairsOrAWallAlone)
{
	BackWall::Params p;
	p.minLength = 0.3;
	// Two faces of a box seen at its corner: the rest of the box is behind
	// each face.
	std::vector<cv::Point2d> box;
	addSegment(box, {2.0, 0.0}, {2.4, 0.4}, 60);
	addSegment(box, {2.0, 0.0}, {2.4, -0.4}, 60);
	EXPECT_FALSE(BackWall::find(box, p).has_value());
	// Risers of a flight: the top one has the others in front of it but
	// reaches no further to the sides.
	std::vector<cv::Point2d> stairs;
	for (int s = 0; s < 5; s++)
		addSegment(stairs, {2.0 + 0.3 * s, -0.5}, {2.0 + 0.3 * s, 0.5}, 50);
	EXPECT_FALSE(BackWall::find(stairs, p).has_value());
	// A wall with nothing in front of it.
	std::vector<cv::Point2d> wall;
	addSegment(wall, {3.0, -1.0}, {3.0, 1.0}, 200);
	EXPECT_FALSE(BackWall::find(wall, p).has_value());
	// Too short.
	std::vector<cv::Point2d> shortWall;
	addSegment(shortWall, {3.0, -0.3}, {3.0, 0.3}, 100);
	addSegment(shortWall, {2.8, -0.1}, {2.8, 0.1}, 50);
	EXPECT_FALSE(BackWall::find(shortWall, {}).has_value());
	p.minLength = 0.5;
	EXPECT_TRUE(BackWall::find(shortWall, p).has_value());
}
