/* semnav: semantic navigation from tilting-laser sweeps */
// Ground-truth maps of scenes (SceneMapBuilder), SemanticMap::addInstance
// and SemanticPlanner's extra obstacles, which navigation relies on.
#include <gtest/gtest.h>
#include <semnav/map/MapIO.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/navsim/SceneMapBuilder.h>
#include <semnav/planning/SemanticPlanner.h>
#include <semnav/sim/SceneLoader.h>

#include <filesystem>

#include "../TestPaths.h"

using namespace semnav;
namespace fs = std::filesystem;

namespace
{

SemanticMap::CellState stateAt(const SemanticMap& m, double x, double y)
{
	int cx, cy;
	EXPECT_TRUE(m.worldToCell(x, y, cx, cy));
	return m.cellState(cx, cy);
}
}  // namespace

TEST(SceneMapBuilder, OfficeGroundTruth)
{
	const Scene s = SceneLoader::loadFile(
	    test::kSourceDir + "/datasets/office/office.yaml");
	SemanticMap map;
	SceneMapBuilder::build(s, map);
	using CS = SemanticMap::CellState;
	EXPECT_EQ(stateAt(map, 2.0, 0.05), CS::Occupied);   // south wall
	EXPECT_EQ(stateAt(map, 3.0, 3.0), CS::Occupied);    // table
	EXPECT_EQ(stateAt(map, 5.0, 4.0), CS::Free);        // hall
	EXPECT_EQ(stateAt(map, 8.0, 3.7), CS::Free);        // passage
	EXPECT_EQ(stateAt(map, 10.1, 2.6), CS::Free);       // inside the U
	EXPECT_EQ(stateAt(map, 10.75, 2.6), CS::Occupied);  // its closed end
	EXPECT_EQ(stateAt(map, -1.0, 4.0), CS::Unknown);    // outside the bounds
	int cx, cy;
	map.worldToCell(3.0, 3.0, cx, cy);
	EXPECT_TRUE(map.labels(cx, cy).contains(Label::Obstacle));
	map.worldToCell(5.0, 4.0, cx, cy);
	EXPECT_TRUE(map.labels(cx, cy).contains(Label::Floor));
	// Instances in scene order: 2 doors, 2 washbasins, 3 wastebaskets, stairs.
	EXPECT_EQ(map.instances().size(), 8u);
	const auto wb = map.instances(Label::Wastebasket);
	ASSERT_EQ(wb.size(), 3u);
	EXPECT_NEAR(wb[2].centroid.x, 11.2, 1e-9);
	EXPECT_NEAR(wb[2].centroid.y, 2.6, 1e-9);
	EXPECT_NEAR(wb[2].extent().x, 0.3, 1e-9);
	EXPECT_FALSE(map.cellsOf(wb[2].id).empty());
	EXPECT_FALSE(map.goalRegion(wb[2].id, 0.6).empty());
	// The map directory keeps them.
	const fs::path dir = fs::temp_directory_path() /
	                     ("semnav_gtmap_" + std::to_string(::getpid()));
	MapIO::save(map, dir.string());
	SemanticMap back;
	MapIO::load(dir.string(), back);
	EXPECT_EQ(back.instances(Label::Wastebasket).size(), 3u);
	fs::remove_all(dir);
}

TEST(SceneMapBuilder, AddInstanceTakesTheNextId)
{
	const Scene s =
	    SceneLoader::loadFile(test::kSourceDir + "/datasets/nav/utrap.yaml");
	SemanticMap map;
	SceneMapBuilder::build(s, map);
	const std::size_t n = map.instances().size();
	const int id = map.addInstance(Label::Door, {1, 1, 0}, {1.5, 1.2, 2}, 3);
	EXPECT_EQ(id, static_cast<int>(n) + 1);
	EXPECT_EQ(map.instance(id).observations, 3u);
	EXPECT_EQ(map.instances(Label::Wastebasket).front().observations, 1000u);
	EXPECT_NEAR(map.instance(id).centroid.x, 1.25, 1e-12);
	EXPECT_EQ(map.cellsOf(id).size(), 10u * 4u);  // 0.5 x 0.2 m at 5 cm
	EXPECT_EQ(SceneMapBuilder::addInstances(s, Label::Wastebasket, map), 2);
	EXPECT_EQ(map.instances(Label::Wastebasket).size(), 4u);
}

TEST(SceneMapBuilder, ExtraObstaclesChangeThePlan)
{
	const Scene s = SceneLoader::loadFile(
	    test::kSourceDir + "/datasets/nav/two_routes.yaml");
	SemanticMap map;
	SceneMapBuilder::build(s, map);
	SemanticPlanner planner(
	    map, CnnPlanner::TOptions(), TraversabilityBuilder::TOptions());
	const auto south =
	    planner.toLabel(1.5, 2.0, Label::Washbasin, CostProfile::Shortest);
	// A wall of sensed points across the south corridor at x = 6.
	std::vector<mrpt::math::TPoint2D> pts;
	for (double y = 0.1; y < 2.5; y += 0.04) pts.push_back({6.0, y});
	planner.setExtraObstacles(pts);
	const auto north =
	    planner.toLabel(1.5, 2.0, Label::Washbasin, CostProfile::Shortest);
	EXPECT_GT(north.path.cost, south.path.cost + 1.0);
	for (const auto& p : north.path.points)
		EXPECT_FALSE(std::abs(p.x - 6.0) < 0.3 && p.y < 2.5);
	planner.setExtraObstacles({});
	EXPECT_DOUBLE_EQ(
	    planner.toLabel(1.5, 2.0, Label::Washbasin, CostProfile::Shortest)
	        .path.cost,
	    south.path.cost);
}
