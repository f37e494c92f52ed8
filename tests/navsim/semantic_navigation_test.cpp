/* semnav: semantic navigation from tilting-laser sweeps */
// End-to-end runs of SemanticNavigator with a simulated robot, on
// ground-truth maps of several scenes (independent of the detectors):
// arrival without collision at the instance the planner's costs call
// nearest (also from inside U-shaped traps), replanning around an obstacle
// the map lacks and after a map change, and typed stops.
#include <gtest/gtest.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/navsim/SceneMapBuilder.h>
#include <semnav/navsim/SimulatedNavigation.h>
#include <semnav/navsim/SimulationConfig.h>
#include <semnav/sim/SceneLoader.h>

#include <cmath>
#include <cstdio>
#include <limits>

#include "../TestPaths.h"
#include "NavTestUtils.h"

using namespace semnav;
using Reason = SemanticNavigator::StopReason;
using Replan = SemanticNavigator::ReplanReason;

namespace
{

Scene scene(const std::string& rel)
{
	return test::sourceScene(rel);
}

/** Path-nearest instance of `label` from (x, y) by the planner's own costs
 * (one plan per instance), and the Euclidean-nearest one. */
std::pair<int, int> nearestInstances(
    const SemanticMap& map, Label label, double x, double y)
{
	SemanticPlanner planner(
	    map, test::shippedNavigationConfig().cnn,
	    test::shippedNavigationConfig().traversability);
	const CostProfile profile =
	    costProfileFromName(test::shippedNavigationConfig().navigator.profile);
	int bestPath = 0, bestEucl = 0;
	double cPath = std::numeric_limits<double>::infinity(), cEucl = cPath;
	for (const auto& o : map.instances(label))
	{
		const double d = std::hypot(o.centroid.x - x, o.centroid.y - y);
		if (d < cEucl)
		{
			cEucl = d;
			bestEucl = o.id;
		}
		try
		{
			const double c = planner.toObject(x, y, o.id, profile).path.cost;
			if (c < cPath)
			{
				cPath = c;
				bestPath = o.id;
			}
		}
		catch (const PlanningError&)
		{
		}
	}
	return {bestPath, bestEucl};
}

struct Case
{
	const char* name;
	const char* scene;
	mrpt::math::TPose2D start;
	Label label;
	bool euclideanDiffers;
};

void PrintTo(const Case& c, std::ostream* os)
{
	*os << c.name;
}

class NavigationRuns : public ::testing::TestWithParam<Case>
{
};
}  // namespace

TEST_P(NavigationRuns, ReachesThePathNearestInstanceWithoutCollision)
{
	const Case& c = GetParam();
	const Scene s = scene(c.scene);
	SemanticMap map(test::shippedNavigationConfig().map);
	SceneMapBuilder::build(s, map);
	const auto [pathNearest, euclNearest] =
	    nearestInstances(map, c.label, c.start.x, c.start.y);
	ASSERT_NE(pathNearest, 0);

	SimulatedNavigation sim(map, s, test::shippedNavigationConfig());
	const auto r = sim.run(NavCommand::nearest(c.label), c.start);
	std::printf(
	    "NAVRUN %s start (%.2f, %.2f, %.0f) '%s': success %d, collisions %d, "
	    "reached %d, path-nearest %d, euclidean-nearest %d, %.2f m from it, "
	    "sim %.1f s, replans %d, wall %.2f s\n",
	    c.scene, c.start.x, c.start.y, c.start.phi * 180 / M_PI,
	    r.command.text().c_str(), r.success, r.collisions, r.objectId,
	    pathNearest, euclNearest, r.distanceToGoal, r.simTime, r.replans,
	    r.wallSeconds);
	EXPECT_TRUE(r.success) << r.message;
	EXPECT_EQ(r.reason, Reason::Reached);
	EXPECT_EQ(r.collisions, 0);
	EXPECT_EQ(r.objectId, pathNearest);
	EXPECT_EQ(r.objectLabel, c.label);
	EXPECT_LT(r.distanceToGoal, 1.0);
	EXPECT_LT(r.simTime, 120.0);
	if (c.euclideanDiffers) EXPECT_NE(euclNearest, pathNearest);
}

INSTANTIATE_TEST_SUITE_P(
    Scenes, NavigationRuns,
    ::testing::Values(
        Case{
            "office_hall",
            "datasets/office/office.yaml",
            {2.2, 1.5, 0},
            Label::Wastebasket,
            false},
        Case{
            "office_utrap",
            "datasets/office/office.yaml",
            {10.1, 2.6, 0},
            Label::Wastebasket,
            false},
        Case{
            "office_washbasin",
            "datasets/office/office.yaml",
            {6.5, 5.0, M_PI / 2},
            Label::Washbasin,
            false},
        Case{
            "utrap_deep",
            "datasets/nav/utrap.yaml",
            {6.2, 2.6, 0},
            Label::Wastebasket,
            true},
        Case{
            "utrap_facing_out",
            "datasets/nav/utrap.yaml",
            {5.0, 2.6, M_PI},
            Label::Wastebasket,
            true},
        Case{
            "two_routes",
            "datasets/nav/two_routes.yaml",
            {1.5, 2.0, 0},
            Label::Washbasin,
            false},
        Case{
            "lab",
            "tests/dataset/scenes/lab.yaml",
            {1.5, 5.0, -M_PI / 3},
            Label::Wastebasket,
            false},
        Case{
            "corridor",
            "tests/dataset/scenes/corridor.yaml",
            {18.5, 1.2, M_PI},
            Label::Wastebasket,
            false}),
    [](const auto& info) { return std::string(info.param.name); });

TEST(SemanticNavigation, ReplansAroundAnObstacleTheMapLacks)
{
	// Map of two_routes; the robot drives in two_routes_blocked, where a
	// crate closes the (shorter) south corridor.
	SemanticMap map(test::shippedNavigationConfig().map);
	SceneMapBuilder::build(scene("datasets/nav/two_routes.yaml"), map);
	const Scene world = scene("datasets/nav/two_routes_blocked.yaml");
	SimulatedNavigation sim(map, world, test::shippedNavigationConfig());
	const auto r =
	    sim.run(NavCommand::nearest(Label::Washbasin), {1.5, 2.0, 0});
	std::printf(
	    "NAVRUN blocked corridor: success %d, collisions %d, replans %d, sim "
	    "%.1f s\n",
	    r.success, r.collisions, r.replans, r.simTime);
	EXPECT_TRUE(r.success) << r.message;
	EXPECT_EQ(r.collisions, 0);
	ASSERT_GE(r.replans, 1);
	EXPECT_NE(r.plans[1].reason, Replan::Initial);
	EXPECT_NE(r.plans[1].reason, Replan::MapChanged);
	EXPECT_FALSE(r.sensedObstacles.empty());
	// The first plan took the south corridor, the robot drove the north one.
	const auto yAt6 = [](const std::vector<mrpt::math::TPoint2D>& path)
	{
		for (const auto& p : path)
			if (std::abs(p.x - 6.0) < 0.1) return p.y;
		return -1.0;
	};
	EXPECT_LT(yAt6(r.plans.front().path), 2.5);
	EXPECT_GT(yAt6(r.plans.back().path), 4.5);
	bool north = false;
	for (const auto& p : r.trajectory)
		if (std::abs(p.x - 6.0) < 0.1 && p.y > 4.5) north = true;
	EXPECT_TRUE(north);
}

TEST(SemanticNavigation, ReplansOnTheNavigatorsBlockedEvents)
{
	// Without the look-ahead on sensed obstacles, only MRPT's events (way
	// blocked, target blocked, navigation error) can trigger the replan.
	SimulationConfig c = SimulationConfig::load(
	    test::kSourceDir + "/config/navigation.ini",
	    test::kSourceDir + "/config/planning.ini",
	    test::kSourceDir + "/config/sim.ini");
	c.navigator.pathCheckDistance = 0;
	SemanticMap map(c.map);
	SceneMapBuilder::build(scene("datasets/nav/two_routes.yaml"), map);
	const Scene world = scene("datasets/nav/two_routes_blocked.yaml");
	SimulatedNavigation sim(map, world, c);
	const auto r =
	    sim.run(NavCommand::nearest(Label::Washbasin), {1.5, 2.0, 0});
	std::printf(
	    "NAVRUN blocked corridor, events only: success %d, collisions %d, "
	    "replans %d (%s), sim %.1f s\n",
	    r.success, r.collisions, r.replans,
	    r.plans.size() > 1
	        ? SemanticNavigator::replanReasonName(r.plans[1].reason)
	        : "-",
	    r.simTime);
	EXPECT_TRUE(r.success) << r.message;
	EXPECT_EQ(r.collisions, 0);
	ASSERT_GE(r.replans, 1);
	const Replan why = r.plans[1].reason;
	EXPECT_TRUE(
	    why == Replan::WayBlocked || why == Replan::TargetBlocked ||
	    why == Replan::NavigatorError)
	    << SemanticNavigator::replanReasonName(why);
}

TEST(SemanticNavigation, ReplansWhenTheMapChanges)
{
	const Scene world = scene("datasets/nav/two_routes.yaml");
	SemanticMap map(test::shippedNavigationConfig().map);
	SceneMapBuilder::build(world, map);
	bool changed = false;
	SimulatedNavigation sim(map, world, test::shippedNavigationConfig());
	const auto r = sim.run(
	    NavCommand::nearest(Label::Washbasin), {1.5, 2.0, 0}, "",
	    [&](double t, SemanticNavigator& nav)
	    {
		    if (changed || t < 2.0) return;
		    // Someone reports the south corridor closed at x = 6.
		    const GridGeometry& g = map.geometry();
		    for (int row = 0; row < g.rows; row++)
			    for (int col = 0; col < g.cols; col++)
			    {
				    const double x = g.centerX(col), y = g.centerY(row);
				    if (std::abs(x - 6.0) < 0.15 && y > 0 && y < 2.6)
				    {
					    map.occupancyGrid().setCell(col, row, 0.95f);
					    map.at("labels", col, row) = static_cast<float>(
					        LabelSet().mask() |
					        (1u << static_cast<int>(Label::Obstacle)));
				    }
			    }
		    map.updateCosts();
		    nav.notifyMapChanged();
		    changed = true;
	    });
	EXPECT_TRUE(changed);
	EXPECT_TRUE(r.success) << r.message;
	EXPECT_EQ(r.collisions, 0);
	ASSERT_GE(r.replans, 1);
	EXPECT_EQ(r.plans[1].reason, Replan::MapChanged);
	for (const auto& p : r.plans.back().path)
		EXPECT_FALSE(std::abs(p.x - 6.0) < 0.1 && p.y < 2.6)
		    << p.x << " " << p.y;
}

TEST(SemanticNavigation, StopsWithNoPathWhenEveryWayIsClosed)
{
	SemanticMap map(test::shippedNavigationConfig().map);
	SceneMapBuilder::build(scene("datasets/nav/two_routes.yaml"), map);
	Scene world = scene("datasets/nav/two_routes_blocked.yaml");
	// Close the north corridor too.
	SceneObject crate;
	crate.label = Label::Obstacle;
	crate.parts.push_back(BoxShape{{6.0, 5.2, 0.5}, {0.3, 1.6, 1.0}, 0});
	world.objects.push_back(crate);
	SimulatedNavigation sim(map, world, test::shippedNavigationConfig());
	const auto r =
	    sim.run(NavCommand::nearest(Label::Washbasin), {1.5, 2.0, 0});
	EXPECT_FALSE(r.success);
	EXPECT_EQ(r.reason, Reason::NoPath) << r.message;
	EXPECT_EQ(r.collisions, 0);
	EXPECT_GE(r.replans, 1);
}

TEST(SemanticNavigation, GivesUpOnNoProgressNotOnAReplanCount)
{
	// Replans on a map that changes nothing (notifyMapChanged every second
	// steps): driving toward the goal shortens the plan, which is progress,
	// so the replans may outnumber max_stalled_replans; when nothing counts
	// as progress (progress_m out of reach) the navigator gives up.
	const Scene world = scene("datasets/nav/two_routes.yaml");
	SemanticMap map(test::shippedNavigationConfig().map);
	SceneMapBuilder::build(world, map);
	const auto run = [&](double progressM)
	{
		SimulationConfig c = test::shippedNavigationConfig();
		c.navigator.maxStalledReplans = 3;
		c.navigator.progressDistance = progressM;
		SimulatedNavigation sim(map, world, c);
		int steps = 0;
		return sim.run(
		    NavCommand::nearest(Label::Washbasin), {1.5, 2.0, 0}, "",
		    [&](double, SemanticNavigator& nav)
		    {
			    if (++steps % 10 == 0) nav.notifyMapChanged();
		    });
	};
	const auto moving = run(0.25);
	EXPECT_TRUE(moving.success) << moving.message;
	EXPECT_GT(moving.replans, 3);
	EXPECT_EQ(moving.collisions, 0);
	const auto stalled = run(1000);
	EXPECT_FALSE(stalled.success);
	EXPECT_EQ(stalled.reason, Reason::NoProgress) << stalled.message;
	EXPECT_EQ(stalled.replans, 3);
}

TEST(SemanticNavigation, BadOrdersAreErrors)
{
	const Scene world = scene("datasets/nav/utrap.yaml");
	SemanticMap map(test::shippedNavigationConfig().map);
	SceneMapBuilder::build(world, map);
	SimulatedNavigation sim(map, world, test::shippedNavigationConfig());
	// A label with no instance: the message lists the map's objects.
	try
	{
		sim.run(NavCommand::nearest(Label::Stairs), {1.5, 1.5, 0});
		FAIL();
	}
	catch (const NoInstanceError& e)
	{
		EXPECT_NE(std::string(e.what()).find("wastebasket"), std::string::npos);
	}
	// An object id that is not of the label, or does not exist.
	EXPECT_THROW(
	    sim.run(NavCommand::object(Label::Washbasin, 1), {1.5, 1.5, 0}), Error);
	EXPECT_THROW(
	    sim.run(NavCommand::object(Label::Washbasin, 99), {1.5, 1.5, 0}),
	    Error);
	// Starts inside an obstacle, too close to a wall, outside the map.
	EXPECT_THROW(
	    sim.run(NavCommand::nearest(Label::Wastebasket), {5.5, 1.95, 0}),
	    Error);
	// Too close to a wall (in the planner's inflated obstacle, not in
	// contact): the plan starts from the nearest free cell.
	{
		const auto close =
		    sim.run(NavCommand::nearest(Label::Wastebasket), {0.45, 3.0, 0});
		EXPECT_TRUE(close.success) << close.message;
		ASSERT_FALSE(close.plans.empty());
		const auto& from = close.plans.front().path.front();
		EXPECT_GT(std::hypot(from.x - 0.45, from.y - 3.0), 0.01);
		EXPECT_LE(
		    std::hypot(from.x - 0.45, from.y - 3.0),
		    test::shippedNavigationConfig().navigator.startSnap + 0.05);
	}
	EXPECT_THROW(
	    sim.run(NavCommand::nearest(Label::Wastebasket), {50, 3.0, 0}), Error);
	// A point goal inside an obstacle has no reachable goal cell.
	EXPECT_THROW(
	    sim.run(NavCommand::point(5.5, 1.95), {1.5, 1.5, 0}), PlanningError);
	// A reachable point goal.
	const auto r = sim.run(NavCommand::point(8.5, 4.5), {1.5, 1.5, 0});
	EXPECT_TRUE(r.success) << r.message;
	EXPECT_LT(r.distanceToGoal, 0.7);
	EXPECT_EQ(r.collisions, 0);
}
