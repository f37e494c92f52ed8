/* semnav: semantic navigation from tilting-laser sweeps */
// Double doors: two door instances side by side in one wall joined into one
// door at their middle (SemanticMap::TOptions::doubleDoorMaxWidth;
// docs/mapping.md, "Objects in the map").
#include <gtest/gtest.h>
#include <semnav/map/SemanticMap.h>

#include <vector>

#include "DoorRegions.h"

using namespace semnav;

namespace
{
/** A door region (robot frame) `width` wide, 2 m high, in the wall x = 3
 * facing the robot, centred at y. */
LabeledRegion leaf(int id, double y, double width)
{
	return test::doorPiece(id, y, 1.0, width, 2.0, 0);
}

/** A sweep of the wall x = 3 (y from -1.5 to 1.5, 1 m up), its points
 * labelled wall where wallAt(y), door elsewhere, with these door
 * regions. */
template <typename F>
LabeledSweep wallWith(const std::vector<LabeledRegion>& regions, F wallAt)
{
	auto pts = test::floorFan(2.5);
	for (double y = -1.5; y <= 1.5; y += 0.02)
		pts.push_back({3.0, y, 1.0, wallAt(y) ? Label::Wall : Label::Door});
	auto f = test::makeFakeSweep(pts);
	f.labeled.regions = regions;
	return f.labeled;
}

/** The join on (2.2 m, as shipped) with the other options as shipped. */
SemanticMap::TOptions joinOn()
{
	SemanticMap::TOptions o;
	o.doubleDoorMaxWidth = 2.2;
	return o;
}

std::vector<ObjectInstance> doors(
    const std::vector<LabeledSweep>& sweeps,
    const SemanticMap::TOptions& o = joinOn())
{
	SemanticMap m(o);
	const auto f = test::makeFakeSweep(test::floorFan(2.5));
	for (const auto& s : sweeps)
		m.insert(f.sweep, s, mrpt::poses::CPose2D(0, 0, 0));
	return m.instances(Label::Door);
}
}  // namespace

TEST(SemanticMap, TheTwoLeavesOfADoubleDoorAreOneDoor)
{
	// Leaves seen 0.8 m wide, 0.1 m apart (centres 0.9 m apart: neither
	// the merge distance nor their footprints join them): one door at
	// their middle.
	const auto doorOnly = [](double) { return false; };
	const auto pair =
	    wallWith({leaf(0, -0.45, 0.8), leaf(1, 0.45, 0.8)}, doorOnly);
	auto d = doors({pair});
	ASSERT_EQ(d.size(), 1u);
	EXPECT_NEAR(d[0].centroid.y, 0.0, 1e-6);
	EXPECT_EQ(d[0].leaves, 2);
	// Later sightings of one leaf keep it at the middle.
	const auto left = wallWith({leaf(0, -0.5, 0.8)}, doorOnly);
	d = doors({pair, left, left});
	ASSERT_EQ(d.size(), 1u);
	EXPECT_NEAR(d[0].centroid.y, (-(0.45 + 0.5 + 0.5) / 3 + 0.45) / 2, 1e-6)
	    << "the middle of the leaves' sightings (-0.45, -0.5, -0.5 | 0.45)";
	// Leaves first seen in different sweeps join too.
	d = doors(
	    {wallWith({leaf(0, -0.45, 0.8)}, doorOnly),
	     wallWith({leaf(0, 0.45, 0.8)}, doorOnly)});
	ASSERT_EQ(d.size(), 1u);
	EXPECT_NEAR(d[0].centroid.y, 0.0, 1e-6);
}

TEST(SemanticMap, TwoRoomsDoorsSideBySideStayTwo)
{
	// A wall between them (0.4 m of cells labelled wall and never door):
	// the doors of two neighbouring rooms.
	const auto d = doors({wallWith(
	    {leaf(0, -0.6, 0.8), leaf(1, 0.6, 0.8)},
	    [](double y) { return std::abs(y) < 0.2; })});
	EXPECT_EQ(d.size(), 2u);
	EXPECT_EQ(
	    doors({wallWith(
	              {leaf(0, -0.6, 0.8), leaf(1, 0.6, 0.8)},
	              [](double) { return false; })})
	        .size(),
	    1u)
	    << "the same two without the wall";
	// Too wide together (2.4 m), or a leaf wider than a leaf.
	const auto none = [](double) { return false; };
	EXPECT_EQ(
	    doors({wallWith({leaf(0, -0.65, 1.1), leaf(1, 0.65, 1.1)}, none)})
	        .size(),
	    2u);
	EXPECT_EQ(
	    doors({wallWith({leaf(0, -0.7, 1.3), leaf(1, 0.5, 0.5)}, none)}).size(),
	    2u);
	// Not in one plane (0.3 m apart across the wall).
	auto back = leaf(1, 0.45, 0.8);
	back.centroid.x = 3.3;
	back.minCorner.x = 3.28;
	back.maxCorner.x = 3.32;
	EXPECT_EQ(doors({wallWith({leaf(0, -0.45, 0.8), back}, none)}).size(), 2u);
	// The join switched off (0).
	SemanticMap::TOptions off;
	off.doubleDoorMaxWidth = 0;
	SemanticMap m(off);
	m.insert(
	    test::makeFakeSweep(test::floorFan(2.5)).sweep,
	    wallWith({leaf(0, -0.45, 0.8), leaf(1, 0.45, 0.8)}, none),
	    mrpt::poses::CPose2D(0, 0, 0));
	EXPECT_EQ(m.instances(Label::Door).size(), 2u);
}

TEST(SemanticMap, AStripBesideADoorIsNoSecondLeaf)
{
	// A 0.8 m door and a 0.4 m strip of wall or jamb beside it that the
	// rules took for a door (indoor_125, 155 of the tuning seeds): not
	// alike, so not the two leaves of one door.
	const auto none = [](double) { return false; };
	const auto sweep = wallWith({leaf(0, -0.1, 0.8), leaf(1, 0.65, 0.4)}, none);
	auto d = doors({sweep});
	ASSERT_EQ(d.size(), 2u);
	EXPECT_NEAR(d[0].centroid.y, -0.1, 1e-6) << "the door stays in place";
	// Without the check (or with the ratio at 0.5) they were joined.
	auto o = joinOn();
	o.doubleDoorMinLeafWidthRatio = 0;
	EXPECT_EQ(doors({sweep}, o).size(), 1u);
	o.doubleDoorMinLeafWidthRatio = 0.5;
	EXPECT_EQ(doors({sweep}, o).size(), 1u);
	// Two alike leaves (0.7 and 0.8 m) are still joined.
	EXPECT_EQ(
	    doors({wallWith({leaf(0, -0.4, 0.8), leaf(1, 0.4, 0.7)}, none)}).size(),
	    1u);
}

TEST(SemanticMap, ALeafOutOfTheDoorsPlaneIsNoSecondLeaf)
{
	// Two alike pieces 0.07 m apart across the wall: a door recessed into
	// its gap and a strip of the wall's face beside it (indoor_110 of the
	// tuning seeds), not two leaves hanging in one plane.
	const auto none = [](double) { return false; };
	auto face = leaf(1, 0.45, 0.8);
	face.centroid.x = 2.93;
	face.minCorner.x = 2.91;
	face.maxCorner.x = 2.95;
	const auto sweep = wallWith({leaf(0, -0.45, 0.8), face}, none);
	EXPECT_EQ(doors({sweep}).size(), 2u);
	// Without the check the plane offset of 0.1 m let them join.
	auto o = joinOn();
	o.doubleDoorMaxLeafOffset = 0;
	EXPECT_EQ(doors({sweep}, o).size(), 1u);
	// 0.03 m apart (normals and depths are noisy): still one door.
	face.centroid.x = 2.97;
	face.minCorner.x = 2.95;
	face.maxCorner.x = 2.99;
	EXPECT_EQ(doors({wallWith({leaf(0, -0.45, 0.8), face}, none)}).size(), 1u);
}
