/* semnav: semantic navigation from tilting-laser sweeps */
// SemanticPlanner with start-bounded repairs: after sensed obstacles on
// and off the path, every shared plan's path is a fresh planner's, bit for
// bit, and every Plan copy holds the fresh planner's field.
#include <gtest/gtest.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/navsim/SceneMapBuilder.h>
#include <semnav/planning/SemanticPlanner.h>
#include <semnav/sim/SceneLoader.h>

#include <random>

#include "../TestPaths.h"

using namespace semnav;

namespace
{

TraversabilityBuilder::TOptions traversabilityOptions()
{
	TraversabilityBuilder::TOptions o;
	o.robotRadius = 0.2;
	return o;
}

/** The error's text, or "" and the plan. */
template <class F>
std::string attempt(const F& f)
{
	try
	{
		f();
	}
	catch (const std::exception& e)
	{
		return e.what();
	}
	return "";
}
}  // namespace

TEST(BoundedReplan, SharedPathsAndCopiedFieldsAreTheFreshPlanners)
{
	SemanticMap map;
	SceneMapBuilder::build(
	    SceneLoader::loadFile(
	        test::kSourceDir + "/datasets/office/office.yaml"),
	    map);
	const CnnPlanner::TOptions cnn;
	SemanticPlanner planner(map, cnn, traversabilityOptions());
	planner.setStartBoundedRepair(true);
	std::mt19937 rng(41);
	std::uniform_real_distribution<double> X(0.5, 11.5), Y(0.5, 7.5);
	double sx = 1.0, sy = 1.0;
	std::vector<mrpt::math::TPoint2D> onPath{{5.0, 4.0}};
	int incomplete = 0;
	for (int step = 0; step < 40; step++)
	{
		// A sensed obstacle on the last path, one anywhere, or none; the
		// robot stays where it is every other step.
		const double x = X(rng), y = Y(rng);
		std::vector<mrpt::math::TPoint2D> obstacles;
		if (step % 3 == 0)
			obstacles = onPath;
		else if (step % 3 == 1)
			obstacles = {{x, y}, {x + 0.05, y}};
		planner.setExtraObstacles(obstacles);
		if (step % 2) sx = X(rng), sy = Y(rng);
		SemanticPlanner fresh(map, cnn, traversabilityOptions());
		fresh.setExtraObstacles(obstacles);
		SemanticPlanner::Plan expected;
		const std::string error = attempt(
		    [&]
		    {
			    expected = fresh.toLabel(
			        sx, sy, Label::Wastebasket, CostProfile::Shortest);
		    });
		SemanticPlanner::SharedPlan shared;
		ASSERT_EQ(
		    attempt(
		        [&]
		        {
			        shared = planner.toLabelShared(
			            sx, sy, Label::Wastebasket, CostProfile::Shortest);
		        }),
		    error)
		    << "step " << step;
		if (!error.empty()) continue;
		EXPECT_EQ(shared.path.cells, expected.path.cells) << "step " << step;
		EXPECT_EQ(shared.path.cost, expected.path.cost) << "step " << step;
		incomplete += !shared.fieldComplete;
		const auto& cells = shared.path.points;
		onPath = {cells[cells.size() / 2]};
		shared = {};  // held, the next repair would copy its field
		if (step % 5 == 4)
		{
			const auto copy = planner.toLabel(
			    sx, sy, Label::Wastebasket, CostProfile::Shortest);
			EXPECT_EQ(copy.field.x, expected.field.x) << "step " << step;
		}
	}
	const auto c = planner.counters();
	EXPECT_GT(c.boundedRepairs, 0u);
	EXPECT_GT(c.pendingFinished, 0u);
	EXPECT_GT(incomplete, 0);
}
