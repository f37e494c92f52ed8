/* semnav: semantic navigation from tilting-laser sweeps */
// A sweep's sighting of a door: its largest door region merged into it, not
// the first (SemanticMap::TOptions::doorSightingLargestRegion;
// docs/mapping.md, "Objects in the map"); its place: the middle of the
// box of a wide region (doorSightingBoxCentreMinWidth).
#include <gtest/gtest.h>
#include <semnav/map/SemanticMap.h>

#include <cmath>
#include <vector>

#include "DoorRegions.h"

using namespace semnav;

namespace
{
/** The door instances after inserting, at the origin, one sweep per list
 * of regions (no door region height limit, no least width). */
std::vector<ObjectInstance> doorsFrom(
    const std::vector<std::vector<LabeledRegion>>& sweeps, bool largest)
{
	SemanticMap::TOptions o;
	o.doorSightingLargestRegion = largest;
	o.doorRegionMaxHeight = 0;  // no limit
	o.doorMinWidth = 0;         // a door seen only as the 0.2 m piece stays
	return test::doorsAfterSweeps(o, sweeps);
}
}  // namespace

TEST(SemanticMap, DoorSightingIsTheSweepsLargestRegion)
{
	// The door rule's 0.2 x 0.1 m piece at the sensor's height, 0.4 m
	// beside the door, comes first in the sweep; the door's own region
	// (0.9 x 2 m) second. Both merge into one instance (0.4 m < the merge
	// distance).
	const auto piece = test::doorPiece(0, 0.4, 0.45, 0.2, 0.1, 150);
	const auto door = test::doorPiece(1, 0.0, 1.0, 0.9, 2.0, 6000);
	auto d = doorsFrom({{piece, door}}, true);
	ASSERT_EQ(d.size(), 1u);
	EXPECT_NEAR(d[0].centroid.y, 0.0, 1e-6) << "the door's region";
	EXPECT_EQ(d[0].observations, 1u);
	ASSERT_EQ(d[0].sightingSizes.size(), 1u);
	EXPECT_NEAR(d[0].sightingSizes[0].z, 2.0, 1e-9);
	// The piece after the door's region changes nothing.
	d = doorsFrom({{door, piece}}, true);
	ASSERT_EQ(d.size(), 1u);
	EXPECT_NEAR(d[0].centroid.y, 0.0, 1e-6);
	// Two sweeps, the piece first in each: both sightings on the door.
	d = doorsFrom({{piece, door}, {piece, door}}, true);
	ASSERT_EQ(d.size(), 1u);
	EXPECT_EQ(d[0].observations, 2u);
	EXPECT_NEAR(d[0].centroid.y, 0.0, 1e-6);
	// Off: the first region merged sets the sighting (the piece's place).
	d = doorsFrom({{piece, door}}, false);
	ASSERT_EQ(d.size(), 1u);
	EXPECT_NEAR(d[0].centroid.y, 0.4, 1e-6);
}

TEST(SemanticMap, FloorToCeilingDoorRegionsMakeNoDoor)
{
	// A 2.6 m high stretch of wall the rules took for a door comes first
	// and would hold the door beside it (its footprint overlaps the
	// door's).
	const auto wall = test::doorPiece(0, 1.0, 1.3, 2.0, 2.6, 800);
	const auto door = test::doorPiece(1, 0.3, 1.0, 0.9, 2.0, 600);
	SemanticMap::TOptions o;
	o.doorRegionMaxHeight = 2.5;
	SemanticMap m(o);
	auto f = test::makeFakeSweep(test::floorFan(2.5));
	f.labeled.regions = {wall, door};
	m.insert(f.sweep, f.labeled, mrpt::poses::CPose2D(0, 0, 0));
	auto d = m.instances(Label::Door);
	ASSERT_EQ(d.size(), 1u);
	EXPECT_NEAR(d[0].centroid.y, 0.3, 1e-6) << "the door alone";
	EXPECT_LT(d[0].maxCorner.z, 2.1);
	// No limit (0): the wall region makes the instance
	// the door joins.
	d = doorsFrom({{wall, door}}, true);
	ASSERT_EQ(d.size(), 1u);
	EXPECT_NEAR(d[0].centroid.y, 1.0, 1e-6);
}

TEST(SemanticMap, DoorCentroidWeighsSightingsByWidth)
{
	// One whole view of a 0.9 m door at y = 0, then two cut views of it
	// (0.4 m of the leaf, centred 0.25 m beside the middle).
	const auto whole = test::doorPiece(0, 0.0, 1.0, 0.9, 2.0, 6000);
	const auto cut = test::doorPiece(0, 0.25, 1.0, 0.4, 2.0, 2500);
	SemanticMap::TOptions o;
	o.doorCentroidMaxWeightWidth = 0;  // plain mean
	auto d = test::doorsAfterSweeps(o, {{whole}, {cut}, {cut}});
	ASSERT_EQ(d.size(), 1u);
	EXPECT_NEAR(d[0].centroid.y, 0.5 / 3, 1e-6);
	// Weighted by width squared: 0.9^2 against 2 x 0.4^2.
	o.doorCentroidMaxWeightWidth = 1.5;
	const double weighted = 2 * 0.16 * 0.25 / (0.81 + 2 * 0.16);
	d = test::doorsAfterSweeps(o, {{whole}, {cut}, {cut}});
	ASSERT_EQ(d.size(), 1u);
	EXPECT_EQ(d[0].observations, 3u);
	EXPECT_NEAR(d[0].centroid.y, weighted, 1e-6);
	// The cut views first: the same.
	d = test::doorsAfterSweeps(o, {{cut}, {cut}, {whole}});
	ASSERT_EQ(d.size(), 1u);
	EXPECT_NEAR(d[0].centroid.y, weighted, 1e-6);
	// Only cut views: their mean.
	d = test::doorsAfterSweeps(o, {{cut}, {cut}});
	ASSERT_EQ(d.size(), 1u);
	EXPECT_NEAR(d[0].centroid.y, 0.25, 1e-6);
	// A region 3 m wide (the door and wall beside it) counts as 1.5 m:
	// against the whole view (0.9 m) at 0, it at 0.28.
	const auto swallowed = test::doorPiece(0, 0.28, 1.0, 3.0, 2.0, 9000);
	d = test::doorsAfterSweeps(o, {{whole}, {swallowed}});
	ASSERT_EQ(d.size(), 1u);
	EXPECT_NEAR(d[0].centroid.y, 0.28 * 2.25 / (0.81 + 2.25), 1e-6);
}

TEST(SemanticMap, DoorsNeverSeenWideAreNotReported)
{
	// A 0.25 m strip (a jamb or a wall edge the rules took for a door),
	// 2 m high, detected in two sweeps.
	const auto strip = test::doorPiece(0, 0.0, 1.0, 0.25, 2.0, 900);
	SemanticMap::TOptions o;
	o.doorMinWidth = 0;  // no check
	EXPECT_EQ(test::doorsAfterSweeps(o, {{strip}, {strip}}).size(), 1u);
	o.doorMinWidth = 0.3;
	EXPECT_TRUE(test::doorsAfterSweeps(o, {{strip}, {strip}}).empty());
	// One sighting at least 0.3 m wide is enough.
	const auto door = test::doorPiece(0, 0.1, 1.0, 0.8, 2.0, 5000);
	EXPECT_EQ(test::doorsAfterSweeps(o, {{strip}, {door}}).size(), 1u);
	// An instance's sightings are still kept: it stays a candidate.
	SemanticMap m(o);
	auto f = test::makeFakeSweep(test::floorFan(2.5));
	f.labeled.regions = {strip};
	m.insert(f.sweep, f.labeled, mrpt::poses::CPose2D(0, 0, 0));
	EXPECT_EQ(m.allInstances().size(), 1u);
	EXPECT_TRUE(m.instances(Label::Door).empty());
}

TEST(SemanticMap, AWideDoorsSightingIsTheMiddleOfItsRegionsBox)
{
	// A 1.9 m double door at y = 0 seen obliquely from y < 0: its box
	// spans y -0.95..0.95, but most of its points are on the near side,
	// so their mean is at y = -0.35 (indoor_8's door 17, 0.39 m off).
	auto door = test::doorPiece(0, 0.0, 1.0, 1.9, 2.0, 9000);
	door.centroid.y = -0.35;
	SemanticMap::TOptions o;
	o.doorSightingBoxCentreMinWidth = 1.2;
	auto d = test::doorsAfterSweeps(o, {{door}});
	ASSERT_EQ(d.size(), 1u);
	EXPECT_NEAR(d[0].centroid.y, 0.0, 1e-6) << "the box's middle";
	EXPECT_NEAR(d[0].centroid.x, 3.0, 1e-6);
	EXPECT_NEAR(d[0].centroid.z, 1.0, 1e-6) << "height: the points' mean";
	// Seen again from the other side (mean at +0.3): still the middle.
	auto other = door;
	other.centroid.y = 0.3;
	d = test::doorsAfterSweeps(o, {{door}, {other}});
	ASSERT_EQ(d.size(), 1u);
	EXPECT_NEAR(d[0].centroid.y, 0.0, 1e-6);
	// A region narrower than 1.2 m keeps the mean of its points.
	auto single = test::doorPiece(0, 0.0, 1.0, 0.9, 2.0, 5000);
	single.centroid.y = -0.1;
	d = test::doorsAfterSweeps(o, {{single}});
	ASSERT_EQ(d.size(), 1u);
	EXPECT_NEAR(d[0].centroid.y, -0.1, 1e-6);
	// A region wider than 2.2 m (door and wall) keeps the mean too.
	o.doorSightingBoxCentreMaxWidth = 2.2;
	auto swallowed = test::doorPiece(0, 0.6, 1.0, 3.0, 2.0, 9000);
	swallowed.centroid.y = 0.2;
	d = test::doorsAfterSweeps(o, {{swallowed}});
	ASSERT_EQ(d.size(), 1u);
	EXPECT_NEAR(d[0].centroid.y, 0.2, 1e-6);
	// Off (0): the points' mean.
	o.doorSightingBoxCentreMinWidth = 0;
	d = test::doorsAfterSweeps(o, {{door}});
	ASSERT_EQ(d.size(), 1u);
	EXPECT_NEAR(d[0].centroid.y, -0.35, 1e-6);
}

TEST(SemanticMap, AWideDoorsSightingIsTheMiddleOfItsFullHeightColumns)
{
	// A 1.9 m double door in the wall x = 3 (y -0.95..0.95, z 0..2) whose
	// region took in a 0.6 m strip of wall beside it, 0.4 m high (y
	// 0.95..1.55): the box's middle is 0.3 m off, the door's columns are
	// centred on it (indoor_115's door 14, a 1.87 m region 0.39 m off).
	auto f = test::makeFakeSweep(test::floorFan(2.5));
	std::vector<test::FakePoint> pts;
	for (double y = -0.95; y <= 0.951; y += 0.05)
		for (double z = 0; z <= 2.001; z += 0.1)
			pts.push_back({3.0, y, z, Label::Door});
	for (double y = 1.0; y <= 1.551; y += 0.05)
		for (double z = 0.8; z <= 1.201; z += 0.1)
			pts.push_back({3.0, y, z, Label::Door});
	auto all = test::floorFan(2.5);
	const int first = static_cast<int>(all.size());
	all.insert(all.end(), pts.begin(), pts.end());
	f = test::makeFakeSweep(all);
	for (int i = first; i < static_cast<int>(all.size()); i++)
		f.labeled.regionIds.at<int32_t>(0, i) = 0;
	auto door = test::doorPiece(0, 0.0, 1.0, 2.5, 2.0, pts.size());
	door.minCorner.y = -0.95;
	door.maxCorner.y = 1.55;
	door.centroid.y = 0.1;
	door.imageBox = cv::Rect(first, 0, static_cast<int>(pts.size()), 1);
	f.labeled.regions = {door};
	const auto doorY = [&](double share)
	{
		SemanticMap::TOptions o;
		o.doorSightingBoxCentreMinWidth = 1.5;
		o.doorSightingBoxCentreMaxWidth = 2.6;
		o.doorSightingFullHeightShare = share;
		SemanticMap m(o);
		m.insert(f.sweep, f.labeled, mrpt::poses::CPose2D(0, 0, 0));
		const auto d = m.instances(Label::Door);
		return d.size() == 1 ? d[0].centroid.y : 99.0;
	};
	EXPECT_NEAR(doorY(0.75), 0.0, 0.03) << "the full-height columns";
	EXPECT_NEAR(doorY(0), 0.3, 1e-6) << "off: the box's middle";
}
