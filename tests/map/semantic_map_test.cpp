/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/poses/CPose3D.h>
#include <octomap/OcTree.h>
#include <semnav/common/ConfigChecks.h>
#include <semnav/common/Error.h>
#include <semnav/map/SemanticMap.h>

#include <algorithm>
#include <tuple>
#include <utility>

#include "../common/SavedAndLoaded.h"
#include "MapTestUtils.h"

using namespace semnav;
using semnav::test::FakePoint;
using semnav::test::floorFan;
using semnav::test::makeFakeSweep;

TEST(SemanticMap, LayerApiAndConversions)
{
	SemanticMap m;
	m.growToInclude(-1, -1, 1, 1);
	const auto& g = m.geometry();
	EXPECT_DOUBLE_EQ(g.resolution, 0.05);
	int cx, cy;
	ASSERT_TRUE(m.worldToCell(0.01, 0.01, cx, cy));
	double x, y;
	ASSERT_TRUE(m.cellToWorld(cx, cy, x, y));
	EXPECT_NEAR(x, 0.025, 1e-9);
	EXPECT_NEAR(y, 0.025, 1e-9);
	EXPECT_FALSE(m.worldToCell(1e3, 0, cx, cy));
	EXPECT_FALSE(m.cellToWorld(-1, 0, x, y));

	EXPECT_TRUE(m.exists("labels"));
	EXPECT_TRUE(m.exists("cost"));
	EXPECT_FALSE(m.exists("elevation"));
	m.add("elevation", 1.5f);
	ASSERT_TRUE(m.worldToCell(0.31, -0.21, cx, cy));
	EXPECT_FLOAT_EQ(m.at("elevation", cx, cy), 1.5f);
	m.at("elevation", cx, cy) = 7.0f;
	EXPECT_THROW(m.get("nonexistent"), Error);
	// Unknown is distinct from free.
	EXPECT_EQ(m.cellState(cx, cy), SemanticMap::CellState::Unknown);

	// Growing keeps contents at the same world place and cell alignment.
	m.growToInclude(-6, -3, 9, 2);
	int cx2, cy2;
	ASSERT_TRUE(m.worldToCell(0.31, -0.21, cx2, cy2));
	EXPECT_FLOAT_EQ(m.at("elevation", cx2, cy2), 7.0f);
	EXPECT_NEAR(std::remainder(m.geometry().originX, 0.05), 0, 1e-9);
	EXPECT_EQ(
	    static_cast<int>(m.occupancyGrid().getSizeX()), m.geometry().cols);
	EXPECT_NEAR(m.occupancyGrid().getXMin(), m.geometry().originX, 1e-4);
	EXPECT_EQ(m.occupancyGrid().x2idx(0.31), cx2);
}

TEST(SemanticMap, InsertionMarksFreeOccupiedAndLabels)
{
	SemanticMap m;
	auto pts = floorFan(3.0);
	// A box face 2 m ahead, 0.1..0.5 m high; a ceiling point above.
	for (double y = -0.2; y <= 0.2; y += 0.02)
		for (double z = 0.1; z <= 0.5; z += 0.1)
			pts.push_back({2.0, y, z, Label::Obstacle});
	pts.push_back({1.0, 0.0, 2.5, Label::Ceiling});
	const auto f = makeFakeSweep(pts);
	m.insert(
	    f.sweep, f.labeled,
	    mrpt::poses::CPose2D(1.0, 2.0, M_PI / 2));  // facing +y

	int cx, cy;
	// The box is 2 m ahead of the robot, i.e. at world (1, 4).
	ASSERT_TRUE(m.worldToCell(1.0, 4.01, cx, cy));
	EXPECT_EQ(m.cellState(cx, cy), SemanticMap::CellState::Occupied);
	EXPECT_TRUE(m.labels(cx, cy).contains(Label::Obstacle));
	EXPECT_GE(m.cost(cx, cy), m.costModel().options().lethalCost);
	// Floor between robot and box: free, labelled floor, cost 0.
	ASSERT_TRUE(m.worldToCell(1.0, 3.0, cx, cy));
	EXPECT_EQ(m.cellState(cx, cy), SemanticMap::CellState::Free);
	EXPECT_TRUE(m.labels(cx, cy).contains(Label::Floor));
	EXPECT_DOUBLE_EQ(m.cost(cx, cy), 0.0);
	// Behind the robot nothing was seen.
	ASSERT_TRUE(m.worldToCell(1.0, 1.0, cx, cy));
	EXPECT_EQ(m.cellState(cx, cy), SemanticMap::CellState::Unknown);
	EXPECT_GE(m.cost(cx, cy), m.costModel().options().unknownCost);
	// The ceiling point labels its cell but occupies nothing.
	ASSERT_TRUE(m.worldToCell(1.0, 3.0, cx, cy));
	EXPECT_TRUE(m.labels(cx, cy).contains(Label::Ceiling));
	EXPECT_EQ(m.sweepsInserted(), 1u);
	EXPECT_GT(m.octree().size(), 0u);
}

TEST(SemanticMap, LaterSweepsClearAnObstacleThatLeft)
{
	SemanticMap m;
	auto withBox = floorFan(3.0);
	for (double y = -0.2; y <= 0.2; y += 0.02)
		withBox.push_back({1.5, y, 0.3, Label::Obstacle});
	const auto a = makeFakeSweep(withBox);
	const mrpt::poses::CPose2D pose(0, 0, 0);
	m.insert(a.sweep, a.labeled, pose);
	int cx, cy;
	ASSERT_TRUE(m.worldToCell(1.5, 0.0, cx, cy));
	ASSERT_EQ(m.cellState(cx, cy), SemanticMap::CellState::Occupied);
	const auto b = makeFakeSweep(floorFan(3.0));
	for (int i = 0; i < 6; i++) m.insert(b.sweep, b.labeled, pose);
	EXPECT_EQ(m.cellState(cx, cy), SemanticMap::CellState::Free);
	EXPECT_LT(m.cost(cx, cy), m.costModel().options().lethalCost);
}

TEST(SemanticMap, DetectionsMergeIntoInstances)
{
	SemanticMap::TOptions o;
	o.minObservations = 2;
	SemanticMap m(o);
	auto f = makeFakeSweep(floorFan(3.0));
	Detection d;
	d.label = Label::Wastebasket;
	d.imageBox = cv::Rect(0, 0, 1, 1);
	d.centroid = {2.0, 0.5, 0.2};
	d.extent = {0.3, 0.3, 0.4};
	f.labeled.detections = {d};
	m.insert(f.sweep, f.labeled, mrpt::poses::CPose2D(0, 0, 0));
	ASSERT_EQ(m.allInstances().size(), 1u);
	EXPECT_TRUE(m.instances().empty())
	    << "a one-off detection must not be reported";
	// Seen again from another pose, 10 cm off: same instance.
	f.labeled.detections[0].centroid = {1.0, 0.6, 0.2};
	m.insert(f.sweep, f.labeled, mrpt::poses::CPose2D(1.1, 0, 0));
	ASSERT_EQ(m.allInstances().size(), 1u);
	const auto inst = m.instances(Label::Wastebasket);
	ASSERT_EQ(inst.size(), 1u);
	EXPECT_EQ(inst[0].observations, 2u);
	EXPECT_NEAR(inst[0].centroid.x, 2.05, 1e-9);
	EXPECT_NEAR(inst[0].centroid.y, 0.55, 1e-9);
	EXPECT_GT(inst[0].extent().x, 0.3);
	// Another label at the same place, and the same label far away: new.
	f.labeled.detections[0].label = Label::Washbasin;
	m.insert(f.sweep, f.labeled, mrpt::poses::CPose2D(0, 0, 0));
	f.labeled.detections[0].label = Label::Wastebasket;
	f.labeled.detections[0].centroid = {2.0, -2.0, 0.2};
	m.insert(f.sweep, f.labeled, mrpt::poses::CPose2D(0, 0, 0));
	EXPECT_EQ(m.allInstances().size(), 3u);
	const auto* near = m.nearestInstance(Label::Wastebasket, {2, 0.5});
	ASSERT_NE(near, nullptr);
	EXPECT_EQ(near->id, inst[0].id);
	EXPECT_EQ(m.nearestInstance(Label::Stairs, {0, 0}), nullptr);
	EXPECT_THROW(m.instance(99), Error);
}

TEST(ObjectInstance, OutlyingSightingsDoNotDragTheCentroid)
{
	// Five sightings of one washbasin at (2.65, 0.3) +- 5 cm, a first
	// detection whose box swallowed a neighbour (0.9 m off) and a false
	// alarm merged by footprint overlap (1.9 m off).
	const std::vector<mrpt::math::TPoint3D> seen = {
	    {3.50, 0.64, 0.6}, {2.65, 0.35, 0.6}, {2.70, 0.30, 0.6},
	    {4.54, 0.79, 0.6}, {2.60, 0.25, 0.6}, {2.66, 0.31, 0.6},
	    {2.64, 0.29, 0.6}};
	ObjectInstance o;
	o.centroid = seen[0];
	o.sightings = {seen[0]};
	o.observations = 1;
	for (std::size_t i = 1; i < seen.size(); i++, o.observations++)
		o.addSighting(seen[i], 0.3);
	EXPECT_NEAR(o.centroid.x, 2.65, 0.01);
	EXPECT_NEAR(o.centroid.y, 0.30, 0.01);
	// The plain mean would be 0.3 m away.
	double mx = 0;
	for (const auto& c : seen) mx += c.x / seen.size();
	EXPECT_GT(std::abs(mx - 2.65), 0.3);
	// Two far-apart sightings: no inlier majority, the plain mean.
	ObjectInstance two;
	two.centroid = {0, 0, 0};
	two.sightings = {two.centroid};
	two.observations = 1;
	two.addSighting({2, 0, 0}, 0.3);
	EXPECT_NEAR(two.centroid.x, 1.0, 1e-9);
}

TEST(ObjectInstance, InlierSightingsLieNearTheirMedian)
{
	ObjectInstance o;
	o.sightings = {{2.6, 0, 0}, {2.7, 0.1, 0}, {4.3, 0, 0}, {2.5, -0.1, 0}};
	const auto in = o.inlierSightings(0.6);
	ASSERT_EQ(in.size(), 3u);
	for (const auto& s : in) EXPECT_LT(s.x, 3.0);
	EXPECT_EQ(o.inlierSightings(2.0).size(), 4u);
	EXPECT_TRUE(ObjectInstance().inlierSightings(1.0).empty())
	    << "no sightings";
}

TEST(ObjectInstance, TypicalSizeIsTheMedianDetectionNotTheUnion)
{
	ObjectInstance o;
	o.minCorner = {0, 0, 0};
	o.maxCorner = {1.6, 1.9, 0.9};  // boxes spread over 1.9 m
	EXPECT_NEAR(o.typicalSize().x, 1.9, 1e-9) << "no sizes: the union";
	o.sightingSizes = {{0.45, 0, 0.7}, {0.5, 0, 0.75}, {1.5, 0, 0.8}};
	EXPECT_NEAR(o.typicalSize().x, 0.5, 1e-9);
	EXPECT_NEAR(o.typicalSize().z, 0.75, 1e-9);
}

namespace
{
/** A sweep with one detection of `label` (robot frame), plus `extra`
 * points on a floor fan. */
semnav::test::FakeSweep detectionSweep(
    Label label, const mrpt::math::TPoint3D& centroid,
    const mrpt::math::TPoint3D& extent, const std::vector<FakePoint>& extra)
{
	auto pts = floorFan(3.0);
	pts.insert(pts.end(), extra.begin(), extra.end());
	auto f = makeFakeSweep(pts);
	Detection d;
	d.label = label;
	d.imageBox = cv::Rect(0, 0, 1, 1);
	d.centroid = centroid;
	d.extent = extent;
	f.labeled.detections = {d};
	return f;
}

/** A flight over x 2.0..3.2, y -0.6..0.6 (robot frame), labelled stairs. */
std::vector<FakePoint> flight()
{
	std::vector<FakePoint> pts;
	for (double x = 2.0; x <= 3.2; x += 0.03)
		for (double y = -0.6; y <= 0.6; y += 0.03)
			pts.push_back({x, y, 0.2 + 0.3 * (x - 2.0), Label::Stairs});
	return pts;
}

/** The flight and a table top (x x0..x1, y -0.3..0.3, 0.7 m high)
 * labelled `label` (stairs: a false detection took it for stairs too). */
std::vector<FakePoint> flightAndTable(
    double x0, double x1, Label label = Label::Stairs)
{
	auto pts = flight();
	for (double x = x0; x <= x1; x += 0.03)
		for (double y = -0.3; y <= 0.3; y += 0.03)
			pts.push_back({x, y, 0.7, label});
	return pts;
}
}  // namespace

TEST(SemanticMap, WashbasinsNeedTheirHeightAndAWall)
{
	const mrpt::poses::CPose2D pose(0, 0, 0);
	std::vector<FakePoint> wall;
	for (double y = -1; y <= 1; y += 0.04)
		for (double z = 0.1; z <= 0.9; z += 0.2)
			wall.push_back({2.5, y, z, Label::Wall});
	// Top 0.6 + 0.6 / 2 = 0.9 m, against a wall 0.3 m behind: reported.
	{
		SemanticMap m;
		const auto f = detectionSweep(
		    Label::Washbasin, {2.2, 0, 0.6}, {0.4, 0.4, 0.6}, wall);
		m.insert(f.sweep, f.labeled, pose);
		EXPECT_EQ(m.instances(Label::Washbasin).size(), 1u);
	}
	// The same free-standing (a table): not reported, unless the check
	// is off.
	for (const double wallDistance : {0.6, 0.0})
	{
		SemanticMap::TOptions o;
		o.washbasinMaxWallDistance = wallDistance;
		SemanticMap m(o);
		const auto f = detectionSweep(
		    Label::Washbasin, {2.2, 0, 0.6}, {0.4, 0.4, 0.6}, {});
		m.insert(f.sweep, f.labeled, pose);
		EXPECT_EQ(m.allInstances().size(), 1u);
		EXPECT_EQ(
		    m.instances(Label::Washbasin).size(), wallDistance > 0 ? 0u : 1u);
	}
	// Against the wall but topping out at 0.4 + 0.3 / 2 = 0.55 m (a chair
	// seat, a side table): not reported.
	{
		SemanticMap m;
		const auto f = detectionSweep(
		    Label::Washbasin, {2.2, 0, 0.4}, {0.4, 0.4, 0.3}, wall);
		m.insert(f.sweep, f.labeled, pose);
		EXPECT_EQ(m.allInstances().size(), 1u);
		EXPECT_TRUE(m.instances(Label::Washbasin).empty());
	}
}

TEST(SemanticMap, StairsCentreOnTheirLabelledCells)
{
	// flight(); the detection's points lean to its near right corner:
	// (2.2, -0.35).
	const mrpt::poses::CPose2D pose(0, 0, 0);
	for (const bool fromCells : {true, false})
	{
		SemanticMap::TOptions o;
		o.stairsCentroidFromCells = fromCells;
		SemanticMap m(o);
		const auto f = detectionSweep(
		    Label::Stairs, {2.2, -0.35, 0.4}, {2.0, 2.0, 0.8}, flight());
		m.insert(f.sweep, f.labeled, pose);
		const auto st = m.instances(Label::Stairs);
		ASSERT_EQ(st.size(), 1u);
		if (fromCells)
		{
			EXPECT_NEAR(st[0].centroid.x, 2.6, 0.06);
			EXPECT_NEAR(st[0].centroid.y, 0.0, 0.06);
		}
		else
			EXPECT_NEAR(st[0].centroid.x, 2.2, 1e-6);
	}
	// Detections that never come down to the floor (a table top taken for
	// stairs): not reported.
	SemanticMap m;
	const auto f = detectionSweep(
	    Label::Stairs, {2.2, -0.35, 0.7}, {1.0, 1.0, 0.2}, flight());
	m.insert(f.sweep, f.labeled, pose);
	EXPECT_EQ(m.allInstances().size(), 1u);
	EXPECT_TRUE(m.instances(Label::Stairs).empty());
}

TEST(SemanticMap, AOneOffStairsLabelBesideAFlightDoesNotMoveIt)
{
	// The flight of the test above, detected in four sweeps; in a fifth a
	// false detection also labels a table beside it (x 3.2..4.0) stairs.
	const auto withTable = flightAndTable(3.23, 4.0);
	const mrpt::poses::CPose2D pose(0, 0, 0);
	for (const double share : {0.25, 0.0})
	{
		SemanticMap::TOptions o;
		o.stairsMinCellShare = share;
		SemanticMap m(o);
		for (int k = 0; k < 5; k++)
		{
			// The false detection's box holds flight and table.
			const auto f = k < 4 ? detectionSweep(
			                           Label::Stairs, {2.6, 0.0, 0.4},
			                           {1.2, 1.2, 0.8}, flight())
			                     : detectionSweep(
			                           Label::Stairs, {3.0, 0.0, 0.4},
			                           {2.0, 1.2, 0.8}, withTable);
			m.insert(f.sweep, f.labeled, pose);
		}
		const auto st = m.instances(Label::Stairs);
		ASSERT_EQ(st.size(), 1u);
		// Labelled in 1 of 5 sweeps: below a quarter of the flight's 5.
		EXPECT_NEAR(st[0].centroid.x, share > 0 ? 2.6 : 3.0, 0.06) << share;
		EXPECT_NEAR(st[0].centroid.y, 0.0, 0.06);
	}
}

TEST(SemanticMap, StairsCentreIgnoresAnOutlyingSighting)
{
	// The flight above, detected in four sweeps; in two more a table
	// 1.7 m beyond its centre (x 4.0..4.6) is taken for stairs, its box so
	// wide that it overlaps the flight's and merges with it.
	const auto withTable = flightAndTable(4.0, 4.6);
	SemanticMap m;
	for (int k = 0; k < 6; k++)
	{
		const auto f = k < 4 ? detectionSweep(
		                           Label::Stairs, {2.6, 0.0, 0.4},
		                           {1.2, 1.2, 0.8}, flight())
		                     : detectionSweep(
		                           Label::Stairs, {4.3, 0.0, 0.4},
		                           {2.6, 1.2, 0.8}, withTable);
		m.insert(f.sweep, f.labeled, mrpt::poses::CPose2D(0, 0, 0));
	}
	const auto st = m.instances(Label::Stairs);
	ASSERT_EQ(st.size(), 1u);
	EXPECT_EQ(st[0].observations, 6u);
	// The table's cells (2 of 6 sweeps) pass the cell share, but no
	// sighting near the median reaches them.
	EXPECT_NEAR(st[0].centroid.x, 2.6, 0.06);
	EXPECT_NEAR(st[0].centroid.y, 0.0, 0.06);
}

TEST(SemanticMap, AWashbasinBesideAFlightIsNoPartOfIt)
{
	// The flight above, beside a washbasin (x 3.3..3.8) that four sweeps
	// label washbasin; in two more a false stairs detection labels it
	// stairs too (test_f: a flight's centre moved 0.38 m).
	SemanticMap m;
	for (int k = 0; k < 6; k++)
	{
		const auto f = detectionSweep(
		    Label::Stairs, {k < 4 ? 2.6 : 3.0, 0.0, 0.4}, {1.2, 1.2, 0.8},
		    flightAndTable(3.3, 3.8, k < 4 ? Label::Washbasin : Label::Stairs));
		m.insert(f.sweep, f.labeled, mrpt::poses::CPose2D(0, 0, 0));
	}
	const auto st = m.instances(Label::Stairs);
	ASSERT_EQ(st.size(), 1u);
	// With the basin's cells the flight's would reach the footprint's edge
	// (x 3.6): centre 2.8.
	EXPECT_NEAR(st[0].centroid.x, 2.6, 0.06);
	EXPECT_NEAR(st[0].centroid.y, 0.0, 0.06);
}

TEST(SemanticMap, ABoxHoldingTwoObjectsDoesNotJoinThem)
{
	// Two wastebaskets 1.1 m apart; the first detection's box held both
	// (centroid between them, box over both), the next ones one each.
	const mrpt::poses::CPose2D pose(0, 0, 0);
	for (const double joinDistance : {0.4, 0.6})
	{
		SemanticMap::TOptions o;
		o.objectMergeDistance = joinDistance;
		SemanticMap m(o);
		const std::vector<std::pair<double, double>> seen = {
		    {0.55, 1.4}, {0.0, 0.3}, {1.1, 0.3}, {0.02, 0.3}, {1.08, 0.3}};
		for (const auto& [y, width] : seen)
		{
			const auto f = detectionSweep(
			    Label::Wastebasket, {2.0, y, 0.2}, {0.3, width, 0.4}, {});
			m.insert(f.sweep, f.labeled, pose);
		}
		if (joinDistance < 0.55)
		{
			ASSERT_EQ(m.allInstances().size(), 3u);
			EXPECT_EQ(m.allInstances()[1].observations, 2u);
			EXPECT_NEAR(m.allInstances()[1].centroid.y, 0.01, 1e-6);
			EXPECT_EQ(m.allInstances()[2].observations, 2u);
			EXPECT_NEAR(m.allInstances()[2].centroid.y, 1.09, 1e-6);
		}
		else
			EXPECT_EQ(m.allInstances().size(), 1u) << "one sighting links all";
	}
}

TEST(SemanticMap, DoubtfulObjectsNeedMoreEvidence)
{
	const mrpt::poses::CPose2D pose(0, 0, 0);
	auto seen = [&](SemanticMap& m, double shapeScore)
	{
		auto f = detectionSweep(
		    Label::Wastebasket, {2.0, 0.2, 0.2}, {0.3, 0.3, 0.4}, {});
		f.labeled.detections[0].shapeScore = shapeScore;
		m.insert(f.sweep, f.labeled, pose);
	};
	// One sure detection is an object; one doubtful one is not, two are.
	{
		SemanticMap m;
		seen(m, 0.99);
		EXPECT_EQ(m.instances(Label::Wastebasket).size(), 1u);
	}
	{
		SemanticMap m;
		seen(m, 0.6);
		ASSERT_EQ(m.allInstances().size(), 1u);
		EXPECT_TRUE(m.instances().empty());
		seen(m, 0.5);
		ASSERT_EQ(m.instances(Label::Wastebasket).size(), 1u);
		EXPECT_DOUBLE_EQ(m.instances()[0].bestShapeScore, 0.6);
	}
	{
		SemanticMap::TOptions o;
		o.unsureMinObservations = 1;
		SemanticMap m(o);
		seen(m, 0.6);
		EXPECT_EQ(m.instances().size(), 1u) << "rule off";
	}
	// Detected in 4 of 7 views: enough for a sure object only.
	SemanticMap m;
	ObjectInstance inst;
	inst.label = Label::Wastebasket;
	inst.observations = 4;
	inst.views = 7;
	inst.bestShapeScore = 1.0;
	EXPECT_TRUE(m.reported(inst));
	inst.bestShapeScore = 0.9;
	EXPECT_FALSE(m.reported(inst));
	inst.views = 6;
	EXPECT_TRUE(m.reported(inst));
}

TEST(SemanticMap, GoalRegionIsFreeCellsWithinReach)
{
	// A toy washbasin (0.35 m high, no wall): the plausibility checks off.
	SemanticMap::TOptions o;
	o.washbasinMinTop = 0;
	o.washbasinMaxWallDistance = 0;
	SemanticMap m(o);
	auto pts = floorFan(1.95);  // the floor up to the basin's foot
	for (double y = -0.1; y <= 0.1; y += 0.02)
		pts.push_back({2.0, y, 0.3, Label::Washbasin});
	auto f = makeFakeSweep(pts);
	Detection d;
	d.label = Label::Washbasin;
	d.imageBox = cv::Rect(static_cast<int>(pts.size()) - 11, 0, 11, 1);
	d.centroid = {2.0, 0.0, 0.3};
	d.extent = {0.1, 0.2, 0.1};
	f.labeled.detections = {d};
	m.insert(f.sweep, f.labeled, mrpt::poses::CPose2D(0, 0, 0));
	const auto objs = m.instances(Label::Washbasin);
	ASSERT_EQ(objs.size(), 1u);
	const auto cells = m.cellsOf(objs[0].id);
	ASSERT_FALSE(cells.empty());
	const auto goal = m.goalRegion(objs[0].id, 0.5);
	ASSERT_FALSE(goal.empty());
	for (const auto& [cx, cy] : goal)
	{
		EXPECT_EQ(m.cellState(cx, cy), SemanticMap::CellState::Free);
		double x, y;
		m.cellToWorld(cx, cy, x, y);
		EXPECT_LT(std::hypot(x - 2.0, y), 0.5 + 0.2);
		EXPECT_LT(x, 2.0) << "free cells are on the robot's side";
	}
}

TEST(SemanticMapOptions, ShippedConfigLoadsAndBadValuesAreRejected)
{
	const auto cfg = openIniFile(
	    std::string(SEMNAV_SOURCE_DIR) + "/config/map.ini",
	    {"SemanticMap", "TravelCost", "SweepAssembler", "NormalImage",
	     "RangeSegmentation", "Roughness", "RuleClassifier"});
	SemanticMap::TOptions o;
	o.loadFromConfigFile(*cfg, "SemanticMap");
	o.cost.loadFromConfigFile(*cfg, "TravelCost");
	EXPECT_DOUBLE_EQ(o.resolution, 0.05);
	EXPECT_DOUBLE_EQ(o.stairsMinDetectionRatio, 0.4) << "shipped value";
	mrpt::config::CConfigFileMemory bad("[SemanticMap]\nresolution_m = 0\n");
	EXPECT_THROW(o.loadFromConfigFile(bad, "SemanticMap"), ConfigError);
	for (const char* badKey :
	     {"washbasin_min_top_m = -1", "washbasin_max_wall_distance_m = 6",
	      "stairs_min_detection_ratio = 1.5", "stairs_max_bottom_m = -0.1",
	      "view_max_bearing_deg = 200", "stairs_centroid_from_cells = maybe",
	      "stairs_min_cell_share = 2", "sure_shape_score = 1.1",
	      "sure_min_detection_ratio = -0.1", "unsure_min_observations = 0",
	      "object_merge_distance_m = 0"})
	{
		mrpt::config::CConfigFileMemory b(
		    std::string("[SemanticMap]\n") + badKey + "\n");
		EXPECT_THROW(o.loadFromConfigFile(b, "SemanticMap"), ConfigError)
		    << badKey;
	}
	// The object rules round-trip through save and load.
	SemanticMap::TOptions changed;
	changed.washbasinMinTop = 0.7;
	changed.washbasinMaxWallDistance = 0.5;
	changed.stairsMinDetectionRatio = 0.3;
	changed.stairsMaxBottom = 0.2;
	changed.viewMaxBearingDeg = 80;
	changed.stairsCentroidFromCells = false;
	changed.stairsMinCellShare = 0.4;
	changed.sureShapeScore = 0.8;
	changed.sureMinDetectionRatio = 0.45;
	changed.unsureMinObservations = 3;
	changed.objectMergeDistance = 0.3;
	changed.unsureOnceMinShapeScore = 0.85;
	changed.sureStairsMaxBottom = 0.25;
	changed.stairsCellMargin = 0.7;
	changed.stairsCellGap = 0.3;
	const SemanticMap::TOptions back =
	    test::savedAndLoaded(changed, "SemanticMap");
	EXPECT_DOUBLE_EQ(back.washbasinMinTop, 0.7);
	EXPECT_DOUBLE_EQ(back.washbasinMaxWallDistance, 0.5);
	EXPECT_DOUBLE_EQ(back.stairsMinDetectionRatio, 0.3);
	EXPECT_DOUBLE_EQ(back.stairsMaxBottom, 0.2);
	EXPECT_DOUBLE_EQ(back.viewMaxBearingDeg, 80);
	EXPECT_FALSE(back.stairsCentroidFromCells);
	EXPECT_DOUBLE_EQ(back.stairsMinCellShare, 0.4);
	EXPECT_DOUBLE_EQ(back.sureShapeScore, 0.8);
	EXPECT_DOUBLE_EQ(back.sureMinDetectionRatio, 0.45);
	EXPECT_EQ(back.unsureMinObservations, 3);
	EXPECT_DOUBLE_EQ(back.objectMergeDistance, 0.3);
	EXPECT_DOUBLE_EQ(back.unsureOnceMinShapeScore, 0.85);
	EXPECT_DOUBLE_EQ(back.sureStairsMaxBottom, 0.25);
	EXPECT_DOUBLE_EQ(back.stairsCellMargin, 0.7);
	EXPECT_DOUBLE_EQ(back.stairsCellGap, 0.3);
	mrpt::config::CConfigFileMemory typo(
	    "[TravelCost]\nrobot_type = hovercraft\n");
	EXPECT_THROW(o.cost.loadFromConfigFile(typo, "TravelCost"), ConfigError);
}

TEST(TravelCostModel, FollowsTheLabels)
{
	TravelCostModel::TOptions o;
	const TravelCostModel wheeled(o);
	o.robotType = TravelCostModel::RobotType::Walking;
	const TravelCostModel walking(o);
	const double L = o.lethalCost;
	LabelSet floor, grass, stairs, wallFloor;
	floor.insert(Label::Floor);
	grass.insert(Label::Grass);
	stairs.insert(Label::Stairs);
	wallFloor.insert(Label::Floor);
	wallFloor.insert(Label::Wall);
	using Occ = TravelCostModel::Occupancy;
	EXPECT_DOUBLE_EQ(wheeled.cost(floor, 1.0, Occ::Free), 0.0);
	EXPECT_GT(
	    wheeled.cost(grass, 0.95, Occ::Free),
	    wheeled.cost(grass, 1.0, Occ::Free));
	EXPECT_DOUBLE_EQ(wheeled.cost(stairs, 1.0, Occ::Free), L);
	EXPECT_LT(walking.cost(stairs, 1.0, Occ::Free), L);
	EXPECT_DOUBLE_EQ(wheeled.cost(wallFloor, 1.0, Occ::Unknown), L);
	EXPECT_DOUBLE_EQ(wheeled.cost(wallFloor, 1.0, Occ::Free), 0.0)
	    << "the wall left";
	EXPECT_DOUBLE_EQ(wheeled.cost(floor, 1.0, Occ::Occupied), L);
	EXPECT_DOUBLE_EQ(
	    wheeled.cost(LabelSet(), NAN, Occ::Unknown), o.unknownCost);
	EXPECT_DOUBLE_EQ(wheeled.cost(LabelSet(), NAN, Occ::Free), 0.0);
}

TEST(SemanticMap, ChangesSinceBoundWhatAnInsertionChanged)
{
	SemanticMap m;
	const auto f0 = makeFakeSweep(floorFan(3.0));
	m.insert(f0.sweep, f0.labeled, mrpt::poses::CPose2D(0, 0, 0));
	const auto& g = m.geometry();
	// Each cell's state, labels, cost and object id.
	const auto snapshot = [&]
	{
		std::vector<float> s;
		for (int cy = 0; cy < g.rows; cy++)
			for (int cx = 0; cx < g.cols; cx++)
				s.insert(
				    s.end(), {static_cast<float>(m.cellState(cx, cy)),
				              static_cast<float>(m.labels(cx, cy).mask()),
				              static_cast<float>(m.cost(cx, cy)),
				              static_cast<float>(m.objectId(cx, cy))});
		return s;
	};
	const auto before = snapshot();
	const std::vector<float> observationsBefore =
	    std::as_const(m).get("observations");
	std::vector<double> occupancyBefore;
	for (int cy = 0; cy < g.rows; cy++)
		for (int cx = 0; cx < g.cols; cx++)
			occupancyBefore.push_back(m.occupancy(cx, cy));
	const std::uint64_t v = m.version();
	EXPECT_TRUE(m.changesSince(v).none());
	// A box 1 m ahead of a robot turned left: inside the grid, no growth.
	auto pts = floorFan(1.5);
	for (double y = -0.2; y <= 0.2; y += 0.02)
		pts.push_back({1.0, y, 0.3, Label::Obstacle});
	const auto f1 = makeFakeSweep(pts);
	const GridGeometry g0 = g;
	m.insert(f1.sweep, f1.labeled, mrpt::poses::CPose2D(1.0, 0.0, 0.5));
	ASSERT_TRUE(m.geometry() == g0);
	const auto after = snapshot();
	const SemanticMap::Changes c = m.changesSince(v);
	ASSERT_FALSE(c.all);
	std::size_t changed = 0;
	for (int cy = 0; cy < g.rows; cy++)
		for (int cx = 0; cx < g.cols; cx++)
			for (int k = 0; k < 4; k++)
			{
				const std::size_t i = 4 * g.index(cy, cx) + k;
				if (before[i] == after[i]) continue;
				changed++;
				EXPECT_TRUE(c.cells.contains(cy, cx)) << cx << ", " << cy;
			}
	EXPECT_GT(changed, 0u);
	EXPECT_LT(
	    static_cast<std::size_t>(c.cells.row1 - c.cells.row0) *
	        (c.cells.col1 - c.cells.col0),
	    g.cellCount() / 2);
	// Observation counts and occupancy: written inside `touched` only.
	std::size_t written = 0;
	for (int cy = 0; cy < g.rows; cy++)
		for (int cx = 0; cx < g.cols; cx++)
			if (observationsBefore[g.index(cy, cx)] !=
			        m.at("observations", cx, cy) ||
			    occupancyBefore[g.index(cy, cx)] != m.occupancy(cx, cy))
			{
				written++;
				EXPECT_TRUE(c.touched.contains(cy, cx)) << cx << ", " << cy;
			}
	EXPECT_GT(written, changed / 4);
	EXPECT_TRUE(
	    c.touched.contains(c.cells.row0, c.cells.col0) &&
	    c.touched.contains(c.cells.row1 - 1, c.cells.col1 - 1));
	// Costs recomputed only where the sweep touched: as everywhere.
	const std::vector<float> cost = std::as_const(m).get("cost");
	m.updateCosts();
	EXPECT_EQ(std::as_const(m).get("cost"), cost);
	// Writes through accessors, growth and old versions: everything.
	const std::uint64_t v2 = m.version();
	m.get("labels");
	EXPECT_TRUE(m.changesSince(v2).all);
	EXPECT_FALSE(m.changesSince(m.version()).all);
	m.markChanged({1, 2, 3, 4});
	const auto one = m.changesSince(m.version() - 1);
	EXPECT_FALSE(one.all);
	EXPECT_EQ(one.cells.row0, 1);
	EXPECT_EQ(one.cells.col1, 4);
	for (std::size_t k = 0; k <= SemanticMap::kChangeHistory; k++)
		m.markChanged({0, 0, 1, 1});
	EXPECT_TRUE(m.changesSince(v2).all);
	m.growToInclude(-20, -20, 20, 20);
	EXPECT_TRUE(m.changesSince(m.version() - 1).all);
}

TEST(SemanticMap, OctreeInnerNodesFollowTheirLeaves)
{
	// Each insertion updates the voxels of its points and the inner nodes
	// above them: the tree equals one updated point by point, its inner
	// nodes all recomputed.
	SemanticMap m;
	octomap::OcTree reference(m.options().resolution);
	for (int k = 0; k < 5; k++)
	{
		auto pts = floorFan(2.0 + 0.3 * k);
		for (double y = -0.3; y <= 0.3; y += 0.01)
			for (double z = 0.1; z <= 1.2; z += 0.02)
				pts.push_back({1.0 + 0.2 * k, y, z, Label::Obstacle});
		const auto f = makeFakeSweep(pts);
		const mrpt::poses::CPose2D pose(0.3 * k, 0.1 * k, 0.4 * k);
		m.insert(f.sweep, f.labeled, pose);
		const mrpt::poses::CPose3D robot(
		    pose.x(), pose.y(), 0, pose.phi(), 0, 0);
		for (int i = 0; i < f.labeled.points.cols; i++)
		{
			const auto& p = f.labeled.points.at<cv::Vec3f>(0, i);
			double x, y, z;
			robot.composePoint(p[0], p[1], p[2], x, y, z);
			reference.updateNode(
			    octomap::point3d(
			        static_cast<float>(x), static_cast<float>(y),
			        static_cast<float>(z)),
			    true, true);
		}
	}
	reference.updateInnerOccupancy();
	const auto values = [](const octomap::OcTree& t)
	{
		std::vector<std::tuple<double, double, double, double, float>> v;
		for (auto it = t.begin_tree(), end = t.end_tree(); it != end; ++it)
			v.emplace_back(
			    it.getX(), it.getY(), it.getZ(), it.getSize(),
			    it->getLogOdds());
		return v;
	};
	const auto inserted = values(std::as_const(m).octree());
	ASSERT_GT(inserted.size(), 100u);
	EXPECT_EQ(inserted, values(reference));
	// Saturated voxels (many points each) reached the clamping bound.
	EXPECT_GT(
	    std::count_if(
	        inserted.begin(), inserted.end(),
	        [&](const auto& n)
	        { return std::get<4>(n) == reference.getClampingThresMaxLog(); }),
	    10);
}
