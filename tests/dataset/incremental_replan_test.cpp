/* semnav: semantic navigation from tilting-laser sweeps */
// SemanticPlanner's incremental replanning: after random changes of a real
// map (obstacle boxes written and cleared, sweeps inserted, sensed
// obstacles, goals switched) every plan equals a fresh planner's, field bit
// for bit; plans on an unchanged map reuse the field.
#include <gtest/gtest.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/navsim/SceneMapBuilder.h>
#include <semnav/planning/SemanticPlanner.h>
#include <semnav/sim/SceneLoader.h>

#include <cstring>
#include <functional>
#include <random>

#include "../TestPaths.h"
#include "../map/MapTestUtils.h"

using namespace semnav;

namespace
{

struct Outcome
{
	std::string error;
	SemanticPlanner::Plan plan;
};

Outcome outcomeOf(const std::function<SemanticPlanner::Plan()>& f)
{
	Outcome o;
	try
	{
		o.plan = f();
	}
	catch (const std::exception& e)
	{
		o.error = typeid(e).name() + std::string(": ") + e.what();
	}
	return o;
}

/** Same error, or same path, u, goals and field (bit for bit). */
void expectSame(const Outcome& a, const Outcome& b, int step)
{
	ASSERT_EQ(a.error, b.error) << "step " << step;
	if (!a.error.empty()) return;
	const auto& fa = a.plan.field.x;
	const auto& fb = b.plan.field.x;
	ASSERT_EQ(fa.size(), fb.size()) << "step " << step;
	std::size_t differ = 0;
	for (std::size_t i = 0; i < fa.size(); i++) differ += fa[i] != fb[i];
	EXPECT_EQ(differ, 0u) << "step " << step;
	EXPECT_EQ(std::memcmp(fa.data(), fb.data(), fa.size() * sizeof(double)), 0)
	    << "step " << step;
	EXPECT_EQ(a.plan.u.values(), b.plan.u.values()) << "step " << step;
	EXPECT_EQ(a.plan.goals.ids(), b.plan.goals.ids()) << "step " << step;
	EXPECT_EQ(a.plan.path.points.size(), b.plan.path.points.size())
	    << "step " << step;
	EXPECT_EQ(a.plan.path.cost, b.plan.path.cost) << "step " << step;
	EXPECT_EQ(a.plan.goalObjectId, b.plan.goalObjectId) << "step " << step;
}

TraversabilityBuilder::TOptions replanTraversabilityOptions()
{
	TraversabilityBuilder::TOptions o;
	o.robotRadius = 0.2;
	return o;
}

CnnPlanner::TOptions cnnOptions()
{
	CnnPlanner::TOptions o;
	o.threads = 2;
	return o;
}
}  // namespace

TEST(IncrementalReplan, RandomChangesGiveTheFreshPlannersPlans)
{
	SemanticMap map;
	SceneMapBuilder::build(
	    SceneLoader::loadFile(
	        test::kSourceDir + "/datasets/office/office.yaml"),
	    map);
	// Direct writes go through references taken once (before the first
	// plan) and are recorded with markChanged() / updateCosts(rect).
	auto& labels = map.get("labels");
	auto& observations = map.get("observations");
	auto& grid = map.occupancyGrid();
	const GridGeometry g = map.geometry();
	SemanticPlanner planner(map, cnnOptions(), replanTraversabilityOptions());
	const int washbasin = map.instances(Label::Washbasin).at(0).id;
	std::mt19937 rng(37);
	std::uniform_real_distribution<double> X(0.5, 11.5), Y(0.5, 7.5);
	const auto writeBox = [&](double x, double y, double side, bool occupied)
	{
		CellRect r;
		for (int cy = 0; cy < g.rows; cy++)
			for (int cx = 0; cx < g.cols; cx++)
			{
				if (std::abs(g.centerX(cx) - x) > side / 2 ||
				    std::abs(g.centerY(cy) - y) > side / 2)
					continue;
				const std::size_t i = g.index(cy, cx);
				grid.setCell(cx, cy, occupied ? 0.95f : 0.05f);
				observations[i] = std::max(observations[i], 1.0f);
				LabelSet s;
				s.insert(occupied ? Label::Obstacle : Label::Floor);
				labels[i] = static_cast<float>(s.mask());
				r.add(cy, cx);
			}
		map.markChanged(r);
		map.updateCosts(r);
	};
	int goal = 0;
	std::vector<mrpt::poses::CPose2D> detectionPoses;
	const std::size_t wastebaskets = map.allInstances().size();
	for (int step = 0; step < 60; step++)
	{
		const int change = step == 0 ? -1 : static_cast<int>(rng() % 6);
		const double x = X(rng), y = Y(rng);
		if (change == 0 || change == 1)
			writeBox(x, y, 0.3 + 0.2 * (rng() % 5), change == 0);
		else if (change == 2)
		{
			// A sweep: floor ahead and a small obstacle, every other time
			// a wastebasket detected there (new, or seen again from an
			// earlier pose: a new instance reported at its second sight).
			const bool detected = rng() % 2;
			auto pts = test::floorFan(2.0);
			const int first = static_cast<int>(pts.size());
			for (double dy = -0.15; dy <= 0.15; dy += 0.03)
				pts.push_back(
				    {1.2, dy, 0.3,
				     detected ? Label::Wastebasket : Label::Obstacle});
			auto f = test::makeFakeSweep(pts);
			mrpt::poses::CPose2D pose(x, y, (rng() % 628) / 100.0);
			if (detected)
			{
				Detection d;
				d.label = Label::Wastebasket;
				d.imageBox =
				    cv::Rect(first, 0, static_cast<int>(pts.size()) - first, 1);
				d.centroid = {1.2, 0, 0.3};
				d.extent = {0.1, 0.3, 0.4};
				f.labeled.detections = {d};
				if (!detectionPoses.empty() && rng() % 2)
					pose = detectionPoses[rng() % detectionPoses.size()];
				detectionPoses.push_back(pose);
			}
			map.insert(f.sweep, f.labeled, pose);
			ASSERT_TRUE(map.geometry() == g) << "the map must not grow";
		}
		else if (change == 3)
		{
			std::vector<mrpt::math::TPoint2D> pts;
			for (int k = 0; k < 10; k++)
				pts.push_back({x + 0.05 * (k % 4), y + 0.05 * (k / 4)});
			if (rng() % 3 == 0) pts.clear();
			planner.setExtraObstacles(pts);
		}
		else if (change == 4)
			goal = (goal + 1) % 3;
		// change 5: none (the same goal from another start)
		const double sx = X(rng), sy = Y(rng);
		const auto plan = [&](const SemanticPlanner& p)
		{
			return outcomeOf(
			    [&]
			    {
				    switch (goal)
				    {
					    case 0:
						    return p.toLabel(
						        sx, sy, Label::Wastebasket,
						        CostProfile::Shortest);
					    case 1:
						    return p.toObject(
						        sx, sy, washbasin, CostProfile::Shortest);
					    default:
						    return p.toPoint(
						        sx, sy, 5.0, 4.0, CostProfile::Shortest);
				    }
			    });
		};
		SemanticPlanner fresh(map, cnnOptions(), replanTraversabilityOptions());
		fresh.setExtraObstacles(planner.extraObstacles());
		expectSame(plan(planner), plan(fresh), step);
		if (HasFatalFailure()) return;
	}
	EXPECT_GT(map.allInstances().size(), wastebaskets);
	const auto c = planner.counters();
	std::printf(
	    "full %zu, repairs %zu (fallbacks %zu), reuses %zu, u partial %zu / "
	    "full %zu\n",
	    c.fullFields, c.repairs, c.repairFallbacks, c.reuses,
	    c.partialTraversability, c.fullTraversability);
	EXPECT_GT(c.repairs, 10u);
	EXPECT_GT(c.reuses, 0u);
	EXPECT_GT(c.partialTraversability, 10u);
	EXPECT_GT(c.changedCells, 0u);
}

TEST(IncrementalReplan, UnchangedMapReusesTheFieldAndChangesRepairIt)
{
	SemanticMap map;
	SceneMapBuilder::build(
	    SceneLoader::loadFile(
	        test::kSourceDir + "/datasets/office/office.yaml"),
	    map);
	SemanticPlanner planner(map, cnnOptions(), replanTraversabilityOptions());
	const auto a = planner.toLabel(5, 4, Label::Wastebasket, CostProfile::Safe);
	EXPECT_EQ(planner.counters().last, SemanticPlanner::FieldUpdate::Full);
	const auto b = planner.toLabel(5, 3, Label::Wastebasket, CostProfile::Safe);
	EXPECT_EQ(planner.counters().last, SemanticPlanner::FieldUpdate::Reuse);
	EXPECT_EQ(a.field.x, b.field.x);
	EXPECT_NE(a.path.points.front().y, b.path.points.front().y);
	// A sensed obstacle on the path: repaired (or recomputed when the
	// repair would touch over a tenth of this small map), as a fresh
	// planner plans.
	const auto& mid = b.path.points[b.path.points.size() / 2];
	planner.setExtraObstacles({mid});
	const auto c = planner.toLabel(5, 3, Label::Wastebasket, CostProfile::Safe);
	EXPECT_EQ(
	    planner.counters().repairs + planner.counters().repairFallbacks, 1u);
	SemanticPlanner fresh(map, cnnOptions(), replanTraversabilityOptions());
	fresh.setExtraObstacles({mid});
	const auto d = fresh.toLabel(5, 3, Label::Wastebasket, CostProfile::Safe);
	EXPECT_EQ(c.field.x, d.field.x);
	EXPECT_GT(c.path.cost, b.path.cost);
	// A shared plan keeps its grids while held; the planner repairs a copy.
	const auto held =
	    planner.toLabelShared(5, 3, Label::Wastebasket, CostProfile::Safe);
	const std::vector<double> heldField = held.field->x;
	planner.setExtraObstacles({});
	const auto e =
	    planner.toLabelShared(5, 3, Label::Wastebasket, CostProfile::Safe);
	EXPECT_EQ(held.field->x, heldField);
	EXPECT_NE(held.field.get(), e.field.get());
	EXPECT_EQ(e.field->x, b.field.x);
	EXPECT_EQ(e.copy().path.cost, b.path.cost);
	// An instance whose footprint holds no cell centre: the map's version
	// moves with no cell changed; the goals follow it.
	planner.setExtraObstacles({});
	const std::uint64_t v = map.version();
	const std::size_t goalCells =
	    planner.toLabel(5, 3, Label::Wastebasket, CostProfile::Safe)
	        .goals.count();
	map.addInstance(
	    Label::Wastebasket, {8.001, 3.701, 0}, {8.01, 3.71, 0.4}, 5);
	ASSERT_TRUE(map.changesSince(v).none());
	ASSERT_NE(map.version(), v);
	const auto f = planner.toLabel(5, 3, Label::Wastebasket, CostProfile::Safe);
	const auto h =
	    SemanticPlanner(map, cnnOptions(), replanTraversabilityOptions())
	        .toLabel(5, 3, Label::Wastebasket, CostProfile::Safe);
	EXPECT_EQ(f.goals.ids(), h.goals.ids());
	EXPECT_EQ(f.field.x, h.field.x);
	EXPECT_GT(f.goals.count(), goalCells);
	// Another profile: from scratch. A write through an accessor: the whole
	// map counts as changed (u rebuilt everywhere, field repaired).
	planner.toLabel(5, 3, Label::Wastebasket, CostProfile::Shortest);
	EXPECT_EQ(planner.counters().last, SemanticPlanner::FieldUpdate::Full);
	const auto before = planner.counters();
	map.get("cost");
	planner.toLabel(5, 3, Label::Wastebasket, CostProfile::Shortest);
	EXPECT_EQ(
	    planner.counters().fullTraversability, before.fullTraversability + 1);
	EXPECT_EQ(planner.counters().fullFields, before.fullFields);
}
