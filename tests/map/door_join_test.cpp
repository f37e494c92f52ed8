/* semnav: semantic navigation from tilting-laser sweeps */
// One door found twice: two reported door instances in one wall, closer
// than TOptions::doorJoinDistance with overlapping footprints, are joined
// (docs/mapping.md, "Objects in the map").
#include <gtest/gtest.h>
#include <semnav/map/SemanticMap.h>

#include <vector>

#include "DoorRegions.h"

using namespace semnav;

namespace
{
/** A door region in the wall x = 3, 2 m high, centred at y. */
LabeledRegion wallDoor(int id, double y, double width)
{
	return test::doorPiece(id, y, 1.0, width, 2.0, 1000);
}

/** The reported doors after one sweep per list of regions, at the
 * origin. */
std::vector<ObjectInstance> joinedDoors(
    const std::vector<std::vector<LabeledRegion>>& sweeps, double joinDistance)
{
	SemanticMap::TOptions o;
	o.doorJoinDistance = joinDistance;
	// This join alone: two alike pieces side by side would otherwise be
	// the leaves of a double door (doubleDoorMaxWidth).
	o.doubleDoorMaxWidth = 0;
	o.doorCentroidMaxWeightWidth = 0;  // each instance's plain mean
	return test::doorsAfterSweeps(o, sweeps);
}
}  // namespace

TEST(SemanticMap, OneDoorFoundTwiceIsJoined)
{
	// Sweep 1: two pieces 0.65 m apart (more than the merge distance, no
	// overlap): two instances. Sweep 2: the door whole, beside the first,
	// whose footprint now overlaps the second's.
	const std::vector<std::vector<LabeledRegion>> sweeps = {
	    {wallDoor(0, 0.0, 0.5), wallDoor(1, 0.65, 0.5)},
	    {wallDoor(0, 0.1, 1.0)}};
	auto d = joinedDoors(sweeps, 0);
	ASSERT_EQ(d.size(), 2u) << "no join";
	d = joinedDoors(sweeps, 0.8);
	ASSERT_EQ(d.size(), 1u);
	// The mean of (0 + 0.1) / 2 (2 detections) and 0.65 (1).
	EXPECT_NEAR(d[0].centroid.y, (2 * 0.05 + 0.65) / 3, 1e-6);
	EXPECT_EQ(d[0].leaves, 1);
	EXPECT_EQ(d[0].observations, 2u);
	// Farther apart than the join distance: two doors.
	EXPECT_EQ(joinedDoors(sweeps, 0.55).size(), 2u);
	// Footprints apart: two doors, however close.
	EXPECT_EQ(
	    joinedDoors({{wallDoor(0, 0.0, 0.5), wallDoor(1, 0.65, 0.5)}}, 0.8)
	        .size(),
	    2u);
	// Not in one wall (0.3 m across): two doors.
	auto back = wallDoor(1, 0.65, 0.5);
	back.centroid.x = 3.3;
	back.minCorner.x = 2.9;
	back.maxCorner.x = 3.32;
	EXPECT_EQ(
	    joinedDoors(
	        {{wallDoor(0, 0.0, 0.5), back}, {wallDoor(0, 0.1, 1.0)}}, 0.8)
	        .size(),
	    2u);
}

TEST(SemanticMap, APieceInsideADoorsFootprintJoinsIt)
{
	// Sweep 1: a door 1.2 m wide at y = 0 and a 0.35 m piece at y = 0.9
	// (footprints apart: two instances). Sweep 2: the door whole, 2.2 m
	// wide at y = 0.1, whose footprint now holds the piece; the piece is
	// 0.85 m from the door's centroid, farther than the join distance
	// (indoor_112: two strips at a double door's edge, 0.76 and 0.93 m
	// from its middle).
	const std::vector<std::vector<LabeledRegion>> sweeps = {
	    {wallDoor(0, 0.0, 1.2), wallDoor(1, 0.9, 0.35)},
	    {wallDoor(0, 0.1, 2.2)}};
	SemanticMap::TOptions o;
	o.doubleDoorMaxWidth = 0;
	o.doorCentroidMaxWeightWidth = 0;
	o.doorJoinContainedShare = 0;
	ASSERT_EQ(test::doorsAfterSweeps(o, sweeps).size(), 2u) << "off";
	o.doorJoinContainedShare = 0.8;
	o.doubleDoorMaxWidth = 2.2;    // the piece's reach
	o.doubleDoorMaxLeafWidth = 0;  // no leaves join
	auto d = test::doorsAfterSweeps(o, sweeps);
	ASSERT_EQ(d.size(), 1u);
	EXPECT_NEAR(d[0].centroid.y, 0.05, 1e-6) << "the door's centroid";
	// A piece seen in more sweeps than the door is no piece of it.
	const std::vector<std::vector<LabeledRegion>> more = {
	    sweeps[0],
	    {wallDoor(1, 0.9, 0.35)},
	    {wallDoor(1, 0.9, 0.35)},
	    sweeps[1]};
	EXPECT_EQ(test::doorsAfterSweeps(o, more).size(), 2u);
}
