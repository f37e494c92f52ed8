/* semnav: semantic navigation from tilting-laser sweeps */
// A class registered at run time ("chair") travels like a built-in one:
// names, map insertion (labelled cells, an instance), the map picture, the
// travel cost, the planner's goals, and the saved map.
#include <gtest/gtest.h>
#include <semnav/common/ClassRegistry.h>
#include <semnav/common/Error.h>
#include <semnav/map/MapIO.h>
#include <semnav/map/MapRenderer.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/planning/SemanticPlanner.h>

#include <filesystem>

#include "../map/MapTestUtils.h"

using namespace semnav;
using namespace semnav::test;

namespace
{
const ClassInfo::Rgb kChairColour{123, 45, 67};

/** Drops the classes a test registered, however it ends. */
struct BuiltInsAfterwards
{
	~BuiltInsAfterwards() { ClassRegistry::instance().resetToBuiltIns(); }
};

ClassInfo chairClass()
{
	ClassInfo c;
	c.name = "chair";
	c.labelColour = {200, 100, 50};
	c.mapColour = kChairColour;
	c.mapStyle = ClassInfo::MapStyle::Instance;
	c.passage = ClassInfo::Passage::Blocking;
	c.instances = ClassInfo::InstanceSource::Detections;
	c.merge = ClassInfo::Merge::BySighting;
	c.goal = true;
	return c;
}

class RegisteredClass : public ::testing::Test
{
protected:
	void SetUp() override
	{
		chair = ClassRegistry::instance().add(chairClass());
	}
	BuiltInsAfterwards m_builtIns;

	static SemanticMap::TOptions mapOptions()
	{
		SemanticMap::TOptions o;
		o.octomap = false;
		return o;
	}

	/** Inserts a floor fan with a chair 2 m ahead of the robot, detected. */
	void insertChairSweep(SemanticMap& m) const
	{
		auto pts = floorFan(3.0);
		const auto first = static_cast<int>(pts.size());
		for (double x = 1.85; x <= 2.15; x += 0.03)
			for (double y = -0.15; y <= 0.15; y += 0.03)
				pts.push_back({x, y, 0.4, chair});
		auto f = makeFakeSweep(pts);
		Detection d;
		d.label = chair;
		d.imageBox =
		    cv::Rect(first, 0, static_cast<int>(pts.size()) - first, 1);
		d.centroid = {2.0, 0.0, 0.4};
		d.extent = {0.4, 0.4, 0.8};
		f.labeled.detections = {d};
		m.insert(f.sweep, f.labeled, mrpt::poses::CPose2D(0, 0, 0));
	}

	Label chair = Label::Unknown;
};
}  // namespace

TEST_F(RegisteredClass, TakesTheNextIdAndItsName)
{
	EXPECT_EQ(static_cast<std::size_t>(chair), kBuiltInLabelCount);
	EXPECT_EQ(labelName(chair), "chair");
	EXPECT_EQ(labelFromName("chair"), chair);
	EXPECT_EQ(labelFromId(static_cast<unsigned>(chair)), chair);
	EXPECT_NE(knownLabelNames().find("chair"), std::string::npos);
	EXPECT_EQ(allLabels().back(), chair);
	EXPECT_THROW(ClassRegistry::instance().add(chairClass()), Error)
	    << "a name is registered once";
	// Built-in ids and names are untouched.
	EXPECT_EQ(labelFromName("wastebasket"), Label::Wastebasket);
	EXPECT_EQ(labelName(Label::Obstacle), "obstacle");
	LabelSet s;
	s.insert(chair);
	EXPECT_TRUE(s.contains(chair));
	EXPECT_EQ(s.labels(), std::vector<Label>{chair});
}

TEST_F(RegisteredClass, IsCarriedThroughMapRenderAndPlan)
{
	SemanticMap m(mapOptions());
	insertChairSweep(m);

	// Map: its cells carry the label and are occupied; it has an instance.
	int cx, cy;
	ASSERT_TRUE(m.worldToCell(2.0, 0.0, cx, cy));
	EXPECT_TRUE(m.labels(cx, cy).contains(chair));
	EXPECT_EQ(m.cellState(cx, cy), SemanticMap::CellState::Occupied);
	const auto chairs = m.instances(chair);
	ASSERT_EQ(chairs.size(), 1u);
	EXPECT_NEAR(chairs[0].centroid.x, 2.0, 1e-6);
	EXPECT_EQ(m.objectId(cx, cy), chairs[0].id);
	EXPECT_GE(m.cost(cx, cy), m.costModel().options().lethalCost);
	EXPECT_EQ(
	    m.costModel().cost(
	        LabelSet(1u << static_cast<unsigned>(chair)), 1.0,
	        TravelCostModel::Occupancy::Free),
	    0.0)
	    << "blocking classes cost nothing once seen free (the object left)";

	// Render: the chair's cells show its colour.
	const cv::Mat img = MapRenderer::render(m, 3);
	const cv::Vec3b bgr(kChairColour.b, kChairColour.g, kChairColour.r);
	int chairPixels = 0;
	const int mapWidth = m.geometry().cols * 3;
	for (int r = 0; r < img.rows; r++)
		for (int c = 0; c < mapWidth; c++)
			chairPixels += img.at<cv::Vec3b>(r, c) == bgr;
	EXPECT_GE(chairPixels, 9) << "at least one cell in the chair's colour";

	// Plan: "go to the nearest chair" by name.
	TraversabilityBuilder::TOptions t;
	EXPECT_GE(t.labelU[static_cast<std::size_t>(chair)], t.L)
	    << "a blocking class is blocked for the planner";
	const SemanticPlanner planner(m, CnnPlanner::TOptions(), t);
	const auto plan = planner.toLabel(
	    0.5, 0.0, labelFromName("chair"), CostProfile::Shortest);
	EXPECT_EQ(plan.goalLabel, chair);
	EXPECT_EQ(plan.goalObjectId, chairs[0].id);
	ASSERT_FALSE(plan.path.points.empty());
	const auto& end = plan.path.points.back();
	EXPECT_LT(std::hypot(end.x - 2.0, end.y), 1.0);
	EXPECT_GT(plan.path.lengthM, 0.5);

	// A class that is no goal is refused by name.
	EXPECT_THROW(
	    planner.toLabel(0.5, 0.0, Label::Floor, CostProfile::Shortest),
	    NoInstanceError);
}

TEST_F(RegisteredClass, SavedMapsKeepItsInstances)
{
	SemanticMap m(mapOptions());
	insertChairSweep(m);
	const auto dir = std::filesystem::temp_directory_path() /
	                 ("semnav_chair_" + std::to_string(::getpid()));
	MapIO::save(m, dir.string());
	SemanticMap loaded(mapOptions());
	MapIO::load(dir.string(), loaded);
	std::filesystem::remove_all(dir);
	ASSERT_EQ(loaded.instances(chair).size(), 1u);
	int cx, cy;
	ASSERT_TRUE(loaded.worldToCell(2.0, 0.0, cx, cy));
	EXPECT_TRUE(loaded.labels(cx, cy).contains(chair));
}

TEST(ClassRegistry, RefusesBadNamesAndTooManyClasses)
{
	const BuiltInsAfterwards builtIns;
	auto& registry = ClassRegistry::instance();
	ClassInfo c;
	c.name = "Chair";
	EXPECT_THROW(registry.add(c), Error);
	c.name = "";
	EXPECT_THROW(registry.add(c), Error);
	for (std::size_t i = registry.size(); i < kMaxLabelCount; i++)
	{
		c.name = "extra" + std::to_string(i);
		registry.add(c);
	}
	c.name = "one_too_many";
	EXPECT_THROW(registry.add(c), Error);
	registry.resetToBuiltIns();
	EXPECT_EQ(registry.size(), kBuiltInLabelCount);
	EXPECT_THROW(labelFromName("extra11"), UnknownLabelError);
}

TEST(ClassRegistry, RegisteredSurfacesCarryTheirCostsAndColour)
{
	const BuiltInsAfterwards builtIns;
	auto& registry = ClassRegistry::instance();
	ClassInfo gravel;
	gravel.name = "gravel";
	gravel.ground = true;
	gravel.passage = ClassInfo::Passage::Surface;
	gravel.travelCost = 0.5;
	gravel.plannerCost = 0.3;
	gravel.roughnessRaisesCost = true;
	gravel.mapStyle = ClassInfo::MapStyle::Area;
	gravel.mapColour = {11, 22, 33};
	const Label g = registry.add(gravel);
	ClassInfo ladder;
	ladder.name = "ladder";
	ladder.passage = ClassInfo::Passage::Surface;
	ladder.travelCost = 3.0;
	ladder.walkingOnly = true;
	const Label l = registry.add(ladder);

	// Travel cost: the registry's cost, plus roughness; walking only.
	TravelCostModel::TOptions o;
	const TravelCostModel wheeled(o);
	const auto one = [](Label x)
	{
		LabelSet s;
		s.insert(x);
		return s;
	};
	const auto free = TravelCostModel::Occupancy::Free;
	EXPECT_DOUBLE_EQ(wheeled.cost(one(g), 1.0, free), 0.5);
	EXPECT_DOUBLE_EQ(
	    wheeled.cost(one(g), 0.5, free), 0.5 + 0.5 * o.grassRoughnessGain);
	EXPECT_DOUBLE_EQ(wheeled.cost(one(l), 1.0, free), o.lethalCost);
	o.robotType = TravelCostModel::RobotType::Walking;
	EXPECT_DOUBLE_EQ(TravelCostModel(o).cost(one(l), 1.0, free), 3.0);
	// Planner defaults.
	const TraversabilityBuilder::TOptions t;
	EXPECT_DOUBLE_EQ(t.labelU[static_cast<std::size_t>(g)], 0.3);
	EXPECT_GE(TraversabilityBuilder(t).labelCost(l), t.L) << "wheeled";

	// A ground class frees its cells and colours them in the picture.
	SemanticMap m;
	std::vector<FakePoint> pts;
	for (double x = 0.5; x <= 2.0; x += 0.03)
		for (double y = -0.3; y <= 0.3; y += 0.03) pts.push_back({x, y, 0, g});
	const auto f = makeFakeSweep(pts);
	m.insert(f.sweep, f.labeled, mrpt::poses::CPose2D(0, 0, 0));
	int cx, cy;
	ASSERT_TRUE(m.worldToCell(1.5, 0.0, cx, cy));
	EXPECT_EQ(m.cellState(cx, cy), SemanticMap::CellState::Free);
	EXPECT_TRUE(m.labels(cx, cy).contains(g));
	const cv::Mat img = MapRenderer::render(m, 1);
	const int row = m.geometry().rows - 1 - cy;
	EXPECT_EQ(img.at<cv::Vec3b>(row, cx), cv::Vec3b(33, 22, 11));
}
