/* semnav: semantic navigation from tilting-laser sweeps */
// GroundBorders: the direction of sidewalk / grass edges near the robot, and
// the Localizer's main-direction correction for a sweep with no walls.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/random/RandomGenerators.h>
#include <semnav/common/Error.h>
#include <semnav/localization/GroundBorders.h>
#include <semnav/localization/Localizer.h>
#include <semnav/localization/MainDirections.h>
#include <semnav/perception/LabeledSweep.h>

#include <cmath>
#include <random>

#include "LocalizationTestUtils.h"

using namespace semnav;
using mrpt::DEG2RAD;

namespace
{
/** Outdoor ground ahead of the robot (x 0.5..6.5 m, y -4..4 m on a 2 cm
 * grid): a 2 m wide sidewalk along direction `angle` (robot frame) through
 * (0, `offset`), grass elsewhere; `flip` of the pixels take the other
 * type at random (label noise: spurious border points). */
LabeledSweep groundSweep(double angle, double offset, double flip)
{
	const int rows = 300, cols = 400;
	LabeledSweep ls;
	ls.indoor = false;
	ls.labels = cv::Mat(rows, cols, CV_8U, cv::Scalar(0));
	ls.points = cv::Mat(rows, cols, CV_32FC3, cv::Scalar(0, 0, 0));
	std::mt19937 rng(5);
	std::uniform_real_distribution<double> u(0, 1);
	for (int r = 0; r < rows; r++)
		for (int c = 0; c < cols; c++)
		{
			const double x = 0.5 + 0.02 * r, y = -4 + 0.02 * c;
			const double across =
			    -std::sin(angle) * x + std::cos(angle) * y - offset;
			bool sidewalk = std::abs(across) <= 1.0;
			if (u(rng) < flip) sidewalk = !sidewalk;
			ls.labels.at<uint8_t>(r, c) =
			    static_cast<uint8_t>(sidewalk ? Label::Sidewalk : Label::Grass);
			ls.points.at<cv::Vec3f>(r, c) = cv::Vec3f(x, y, 0);
		}
	return ls;
}
}  // namespace

TEST(GroundBorders, DirectionOfAPathsEdgesDespiteLabelNoise)
{
	const GroundBorders b;
	for (const double deg : {7.0, -12.0, 30.0})
	{
		const auto dir = b.direction(groundSweep(DEG2RAD(deg), 0.3, 0.005));
		ASSERT_TRUE(dir) << deg;
		// Modulo 90 deg: 30 deg reads as -60 + 90.
		EXPECT_NEAR(
		    MainDirections::wrapQuarter(*dir - DEG2RAD(deg)), 0, DEG2RAD(0.5))
		    << deg;
	}
	// Both edges are found, each about as long as it is in range.
	const auto segs = b.segments(b.points(groundSweep(0, 0, 0)));
	ASSERT_EQ(segs.size(), 2u);
	for (const auto& s : segs)
	{
		EXPECT_NEAR(std::abs(s.p0.y), 1.0, 0.05);
		EXPECT_GT(s.length(), 3.5);
	}
}

TEST(GroundBorders, NoDirectionIndoorsWithoutBordersOrFarAway)
{
	const GroundBorders b;
	LabeledSweep indoor = groundSweep(0, 0, 0);
	indoor.indoor = true;
	EXPECT_FALSE(b.direction(indoor));
	// A path across, its near edge 4.6 m ahead: beyond max_range_m (4.5 m).
	EXPECT_FALSE(b.direction(groundSweep(DEG2RAD(90), -5.6, 0)));
	// Stray pixels alone (no path in view): no border line.
	EXPECT_FALSE(b.direction(groundSweep(0, 8, 0.001)));
}

TEST(GroundBorders, LeavesTheFiltersRandomStreamAlone)
{
	auto& rng = mrpt::random::getRandomGenerator();
	rng = mrpt::random::CRandomGenerator(42);
	mrpt::random::CRandomGenerator copy(42);
	const GroundBorders b;
	ASSERT_TRUE(b.direction(groundSweep(DEG2RAD(5), 0, 0.005)));
	EXPECT_EQ(rng.drawUniform32bit(), copy.drawUniform32bit());
}

TEST(GroundBorders, OptionsAreValidated)
{
	GroundBorders::TOptions o;
	mrpt::config::CConfigFileMemory c;
	c.write("GroundBorders", "min_range_m", 5);
	c.write("GroundBorders", "max_range_m", 4);
	EXPECT_THROW(o.loadFromConfigFile(c, "GroundBorders"), ConfigError);
	mrpt::config::CConfigFileMemory d;
	d.write("GroundBorders", "max_correction_deg", 60);
	EXPECT_THROW(o.loadFromConfigFile(d, "GroundBorders"), ConfigError);
	mrpt::config::CConfigFileMemory e;
	e.write("GroundBorders", "enabled", "false");
	e.write("GroundBorders", "max_correction_deg", 10);
	o.loadFromConfigFile(e, "GroundBorders");
	EXPECT_FALSE(o.enabled);
	EXPECT_NEAR(o.maxCorrection, DEG2RAD(10), 1e-12);
}

// A sweep with no wall samples but a direction (its ground borders') gets
// the main-direction correction: the odometry's 6 deg heading error goes.
// Without the direction the heading follows the odometry.
TEST(Localizer, WallLessSweepWithADirectionIsHeadingCorrected)
{
	WallMap map;
	map.addSegments(test::roomWalls());
	map.rebuild();
	const mrpt::poses::CPose2D start(2, 2, 0), truth(3, 2, 0);
	mrpt::poses::CPose2D incr = truth - start;
	incr.phi(DEG2RAD(6));  // odometry heading error
	for (const bool withDirection : {true, false})
	{
		Localizer loc{Localizer::TOptions()};
		loc.setWallMap(&map);
		loc.initialize(start);
		WallObservation none;
		if (withDirection) none.dominantDirection = 0.0;
		const auto u = loc.update(incr, none);
		EXPECT_EQ(u.headingCorrected, withDirection);
		if (withDirection)
			EXPECT_LT(std::abs(u.pose.phi()), DEG2RAD(1.5));
		else
			EXPECT_GT(std::abs(u.pose.phi()), DEG2RAD(4));
	}
}
