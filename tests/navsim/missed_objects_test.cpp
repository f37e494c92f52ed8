/* semnav: semantic navigation from tilting-laser sweeps */
// Negative evidence in the uniqueness check: twin offices that differ only by
// a wastebasket in one. From the office without it, nothing the robot sees
// tells the twins apart; not seeing the wastebasket where the other office
// would show it does.
#include <gtest/gtest.h>
#include <mrpt/math/wrap2pi.h>
#include <semnav/detection/CascadeDetector.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/nav/NavigationErrors.h>
#include <semnav/nav/StopAndScanLocalizer.h>
#include <semnav/navsim/SceneMapBuilder.h>
#include <semnav/sim/SceneLoader.h>
#include <semnav/sim/SimulatedRobot.h>

#include <cmath>
#include <iostream>

#include "../nav/ShippedOptions.h"
#include "NavTestUtils.h"

using namespace semnav;

namespace
{
/** Two identical closed 5 m x 4 m offices side by side (A: x 0..5, B: x
 * 5.3..10.3), with the same wall stub; only office B holds a wastebasket.
 * From inside, the walls of one are the other's. */
const Scene& twinOffices()
{
	static const Scene s = SceneLoader::parse(
	    R"(
name: twin_offices_small
bounds: [0, 0, 10.3, 4]
ceiling_height: 2.6
objects:
  - {label: wall, box: {center: [2.5, 0.05, 1.3], size: [5, 0.1, 2.6]}}
  - {label: wall, box: {center: [2.5, 3.95, 1.3], size: [5, 0.1, 2.6]}}
  - {label: wall, box: {center: [0.05, 2, 1.3], size: [0.1, 3.8, 2.6]}}
  - {label: wall, box: {center: [4.95, 2, 1.3], size: [0.1, 3.8, 2.6]}}
  - {label: wall, box: {center: [7.8, 0.05, 1.3], size: [5, 0.1, 2.6]}}
  - {label: wall, box: {center: [7.8, 3.95, 1.3], size: [5, 0.1, 2.6]}}
  - {label: wall, box: {center: [5.35, 2, 1.3], size: [0.1, 3.8, 2.6]}}
  - {label: wall, box: {center: [10.25, 2, 1.3], size: [0.1, 3.8, 2.6]}}
  # the same wall stub in both: the offices are not symmetric in themselves
  - {label: wall, box: {center: [1.2, 3.4, 1.3], size: [0.1, 1.0, 2.6]}}
  - {label: wall, box: {center: [6.5, 3.4, 1.3], size: [0.1, 1.0, 2.6]}}
  - {label: wastebasket, cylinder: {center: [9.8, 0.6, 0.2], radius: 0.15, height: 0.4}}
trajectory:
  - [2.5, 2.5, 0]
)",
	    "twin_offices_small");
	return s;
}

struct Outcome
{
	bool accepted = false;
	double errorXY = 0;
	std::string message;
};

Outcome startIn(
    const SemanticMap& map, const mrpt::math::TPose2D& start, double weight)
{
	const auto& config = test::shippedNavigationConfig();
	auto o = config.stopAndScan;
	o.missedObjectWeight = weight;
	const auto cascades = CascadeDetector::TOptions::fromIniFile(
	    test::sourceDir() + "/config/cascade.ini");
	StopAndScanLocalizer loc(
	    map, o, test::shippedLocalizationOptions(),
	    test::shippedPerceptionOptions(), cascades);
	SimulatedRobot robot(twinOffices(), config.robot, start);
	robot.enableOdometryNoise(twinOffices().odometry);
	Outcome out;
	try
	{
		const auto rep =
		    loc.start(robot.interfaces(), StopAndScanLocalizer::Mode::Global);
		out.accepted = true;
		out.errorXY = rep.errorXY;
		out.message = "accepted after " + std::to_string(rep.sweeps) +
		              " sweeps, error " + std::to_string(rep.errorXY) + " m";
	}
	catch (const LocalizationFailedError& e)
	{
		out.message = e.what();
	}
	return out;
}
}  // namespace

TEST(MissedObjects, TheWastebasketNotSeenTellsTheTwinOfficesApart)
{
	SemanticMap map(test::shippedNavigationConfig().map);
	SceneMapBuilder::build(twinOffices(), map);
	// The robot in office A, which has no wastebasket; its twin pose in
	// office B would see the wastebasket when it turns.
	const mrpt::math::TPose2D start(2.5, 2.5, 0);
	const Outcome without = startIn(map, start, 0);
	std::cerr << "without negative evidence: " << without.message << "\n";
	// Nothing else tells the offices apart: never accepted at the twin.
	if (without.accepted) EXPECT_LT(without.errorXY, 0.3);
	const Outcome with = startIn(
	    map, start,
	    test::shippedNavigationConfig().stopAndScan.missedObjectWeight);
	std::cerr << "with negative evidence: " << with.message << "\n";
	ASSERT_TRUE(with.accepted) << with.message;
	EXPECT_LT(with.errorXY, 0.15);
	// The check is what decides: without it the start is refused.
	EXPECT_FALSE(without.accepted) << without.message;
}
