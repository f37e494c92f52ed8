/* semnav: semantic navigation from tilting-laser sweeps */
// SemanticPlanner on hand-made maps: "nearest" is the least path cost, not
// the Euclidean distance; a goal behind a wall is reached around it.
#include <gtest/gtest.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/planning/SemanticPlanner.h>

#include <cmath>

using namespace semnav;

namespace
{
/** A 6 m x 4 m room, all seen free, an optional wall at x = 3 from y = 0
 * to 3.4 (passage above), and two wastebaskets: A at (3.6, 1) just behind
 * the wall, B at (0.6, 1). */
void buildRoom(SemanticMap& m, bool wall)
{
	GridGeometry g(0.05, 0, 0, 120, 80);
	std::map<std::string, std::vector<float>> layers;
	for (const auto& name : m.layers())
		layers[name] = std::vector<float>(g.cellCount(), 0.0f);
	std::vector<int8_t> logodds(
	    g.cellCount(), mrpt::maps::COccupancyGridMap2D::p2l(0.1f));
	auto& labels = layers["labels"];
	auto& objects = layers["objects"];
	auto& obs = layers["observations"];
	std::fill(obs.begin(), obs.end(), 1.0f);
	LabelSet floor, basket, wallSet;
	floor.insert(Label::Floor);
	basket.insert(Label::Wastebasket);
	wallSet.insert(Label::Wall);
	std::fill(labels.begin(), labels.end(), static_cast<float>(floor.mask()));
	auto occupy = [&](int col, int row, LabelSet ls, int id)
	{
		const std::size_t i = g.index(row, col);
		logodds[i] = mrpt::maps::COccupancyGridMap2D::p2l(0.95f);
		labels[i] = ls.mask();
		objects[i] = static_cast<float>(id);
	};
	if (wall)
		for (int row = 0; row < 68; row++) occupy(60, row, wallSet, 0);
	std::vector<ObjectInstance> objs;
	int id = 1;
	for (double x : {3.6, 0.6})
	{
		for (int row = 18; row < 22; row++)
			for (int col = static_cast<int>(x / 0.05) - 2;
			     col < static_cast<int>(x / 0.05) + 2; col++)
				occupy(col, row, basket, id);
		ObjectInstance o;
		o.id = id++;
		o.label = Label::Wastebasket;
		o.centroid = {x, 1.0, 0.2};
		o.minCorner = {x - 0.1, 0.9, 0};
		o.maxCorner = {x + 0.1, 1.1, 0.4};
		o.observations = 3;
		objs.push_back(o);
	}
	m.restore(g, std::move(layers), logodds, std::move(objs), 1);
	m.updateCosts();
}

SemanticPlanner::Plan plan(
    const SemanticMap& m, CostProfile profile = CostProfile::Shortest)
{
	return SemanticPlanner(
	           m, CnnPlanner::TOptions(), TraversabilityBuilder::TOptions())
	    .toLabel(2.4, 1.0, Label::Wastebasket, profile);
}
}  // namespace

TEST(SemanticPlanner, NearestIsTheLeastCostNotTheEuclideanNearest)
{
	SemanticMap withWall;
	buildRoom(withWall, true);
	// A is 1.2 m away (Euclidean) behind the wall, B 1.8 m in the open.
	const auto p = plan(withWall);
	EXPECT_EQ(p.goalObjectId, 2) << "went for the wastebasket behind the wall";
	EXPECT_LT(p.path.lengthM, 2.0);
	const auto* euclid =
	    withWall.nearestInstance(Label::Wastebasket, {2.4, 1.0});
	ASSERT_NE(euclid, nullptr);
	EXPECT_EQ(euclid->id, 1);

	SemanticMap open;
	buildRoom(open, false);
	EXPECT_EQ(plan(open).goalObjectId, 1) << "without the wall A is nearest";
}

TEST(SemanticPlanner, GoalBehindAWallIsReachedAroundIt)
{
	SemanticMap m;
	buildRoom(m, true);
	const auto p =
	    SemanticPlanner(
	        m, CnnPlanner::TOptions(), TraversabilityBuilder::TOptions())
	        .toObject(2.4, 1.0, 1, CostProfile::Safe);
	EXPECT_EQ(p.goalObjectId, 1);
	ASSERT_FALSE(p.path.points.empty());
	double maxY = 0;
	for (const auto& q : p.path.points) maxY = std::max(maxY, q.y);
	EXPECT_GT(maxY, 3.4) << "the path must pass the wall's open end";
	// Every path cell is traversable and the cost is the sum along it.
	double cost = 0;
	for (std::size_t i = 1; i < p.path.cells.size(); i++)
	{
		const auto &a = p.path.cells[i - 1], &b = p.path.cells[i];
		ASSERT_FALSE(p.u.blocked(b.row, b.col));
		cost += 0.05 * std::hypot(a.row - b.row, a.col - b.col) +
		        p.u.u(b.row, b.col);
	}
	EXPECT_NEAR(cost, p.path.cost, 1e-6 * cost);
	EXPECT_THROW(
	    SemanticPlanner(
	        m, CnnPlanner::TOptions(), TraversabilityBuilder::TOptions())
	        .toLabel(2.4, 1.0, Label::Washbasin, CostProfile::Shortest),
	    NoInstanceError);
}

TEST(SemanticPlanner, AnObjectTheMapDoesNotReportIsNoGoal)
{
	SemanticMap m;
	buildRoom(m, false);
	// A 4 cm "door": a candidate below door_min_height_m, not an object.
	const int tiny =
	    m.addInstance(Label::Door, {4.0, 2.0, 0.4}, {4.1, 2.1, 0.44});
	ASSERT_FALSE(m.reported(m.instance(tiny)));
	const SemanticPlanner planner(
	    m, CnnPlanner::TOptions(), TraversabilityBuilder::TOptions());
	try
	{
		planner.toObject(2.4, 1.0, tiny, CostProfile::Shortest);
		FAIL() << "planned to a candidate";
	}
	catch (const NoInstanceError& e)
	{
		EXPECT_EQ(
		    std::string(e.what()),
		    "the map has no object " + std::to_string(tiny) +
		        " (objects: wastebasket 1, wastebasket 2)");
	}
	EXPECT_EQ(
	    planner.toObject(2.4, 1.0, 2, CostProfile::Shortest).goalObjectId, 2);
}
