/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <semnav/localization/MainDirections.h>

#include "LocalizationTestUtils.h"

using namespace semnav;
using mrpt::DEG2RAD;

TEST(MainDirections, WrapQuarterHasPeriod90Degrees)
{
	EXPECT_NEAR(MainDirections::wrapQuarter(DEG2RAD(10)), DEG2RAD(10), 1e-12);
	EXPECT_NEAR(MainDirections::wrapQuarter(DEG2RAD(100)), DEG2RAD(10), 1e-12);
	EXPECT_NEAR(MainDirections::wrapQuarter(DEG2RAD(-80)), DEG2RAD(10), 1e-12);
	EXPECT_NEAR(MainDirections::wrapQuarter(DEG2RAD(50)), DEG2RAD(-40), 1e-12);
	EXPECT_NEAR(MainDirections::wrapQuarter(DEG2RAD(190)), DEG2RAD(10), 1e-12);
}

TEST(MainDirections, ManhattanWallsGiveTheirDirectionDespiteAnOddWall)
{
	std::vector<WallSegment> walls;
	const mrpt::poses::CPose2D rot(0, 0, DEG2RAD(17));
	for (const auto& s : test::roomWalls()) walls.push_back(s.transformed(rot));
	walls.push_back(test::seg(0, 0, 2 * std::cos(0.7), 2 * std::sin(0.7)));
	const auto d = MainDirections::estimate(walls, DEG2RAD(5), 1.0, 0.5);
	ASSERT_TRUE(d);
	EXPECT_NEAR(*d, DEG2RAD(17), DEG2RAD(0.01));
}

TEST(MainDirections, NoDirectionWhenTheWallsDisagreeOrAreShort)
{
	// Short walls only.
	EXPECT_FALSE(MainDirections::estimate(
	    {test::seg(0, 0, 0.5, 0), test::seg(0, 0, 0, 0.4)}, DEG2RAD(5), 1.5,
	    0.5));
	// Three walls at 0, 30 and 60 deg (mod 90: no majority).
	std::vector<WallSegment> w;
	for (double a : {0.0, 30.0, 60.0})
		w.push_back(test::seg(
		    0, 0, 3 * std::cos(DEG2RAD(a)), 3 * std::sin(DEG2RAD(a))));
	EXPECT_FALSE(MainDirections::estimate(w, DEG2RAD(5), 1.5, 0.5));
}

TEST(MainDirections, CorrectionAlignsTheObservedDirectionWithTheMap)
{
	// Map walls at 5 deg (mod 90); a robot truly at yaw 30 deg sees them at
	// -25 deg; a particle at yaw 52 deg is moved back to 30 deg.
	const double map = DEG2RAD(5), observed = DEG2RAD(-25);
	EXPECT_NEAR(
	    DEG2RAD(52) + MainDirections::correction(DEG2RAD(52), observed, map),
	    DEG2RAD(30), 1e-12);
	EXPECT_NEAR(
	    DEG2RAD(12) + MainDirections::correction(DEG2RAD(12), observed, map),
	    DEG2RAD(30), 1e-12);
	// 90 deg away is equivalent: yaw 120 stays (mod 90 ambiguity).
	EXPECT_NEAR(
	    MainDirections::correction(DEG2RAD(120), observed, map), 0, 1e-12);
}
