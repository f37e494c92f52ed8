/* semnav: semantic navigation from tilting-laser sweeps */
// Stairs in the map: the flight's centre from its labelled cells beyond the
// detection boxes, and sure flights whose lowest riser no box held
// (docs/mapping.md, "Objects in the map").
#include <gtest/gtest.h>
#include <semnav/map/SemanticMap.h>

#include <cmath>
#include <vector>

#include "MapTestUtils.h"

using namespace semnav;
using semnav::test::FakePoint;
using semnav::test::floorFan;
using semnav::test::makeFakeSweep;

namespace
{
/** A flight over x 2.0..3.2, y -0.6..0.6 (robot frame) seen from below:
 * only its five risers (0.3 m apart) are labelled stairs, its upper treads
 * are hidden. */
std::vector<FakePoint> risers()
{
	std::vector<FakePoint> pts = floorFan(3.0);
	for (int k = 0; k < 5; k++)
		for (double y = -0.6; y <= 0.6; y += 0.03)
			for (double z = 0.02; z < 0.17; z += 0.05)
				pts.push_back({2.0 + 0.3 * k, y, 0.17 * k + z, Label::Stairs});
	return pts;
}
}  // namespace

namespace
{
/** The instance of one sweep holding `pts`, detected in a box over x
 * 2.0..2.4, y -0.6..0 (the near right corner of the flight). */
ObjectInstance cornerDetected(
    const std::vector<FakePoint>& pts, const SemanticMap::TOptions& o)
{
	SemanticMap m(o);
	auto f = makeFakeSweep(pts);
	Detection d;
	d.label = Label::Stairs;
	d.imageBox = cv::Rect(0, 0, 1, 1);
	d.centroid = {2.2, -0.3, 0.2};
	d.extent = {0.4, 0.6, 0.4};
	f.labeled.detections = {d};
	m.insert(f.sweep, f.labeled, mrpt::poses::CPose2D(0, 0, 0));
	const auto st = m.instances(Label::Stairs);
	EXPECT_EQ(st.size(), 1u);
	return st.empty() ? ObjectInstance() : st[0];
}

ObjectInstance cornerDetected(
    const std::vector<FakePoint>& pts, double margin, double gap)
{
	SemanticMap::TOptions o;
	o.stairsCellMargin = margin;
	o.stairsCellGap = gap;
	o.stairsRiserGap = 0;
	return cornerDetected(pts, o);
}

/** Distance of `o`'s centroid from the flight's centre (2.6, 0). */
double offCentre(const ObjectInstance& o)
{
	return std::hypot(o.centroid.x - 2.6, o.centroid.y);
}

}  // namespace

TEST(SemanticMap, AFlightsCentreTakesInCellsBeyondItsBoxes)
{
	// indoor_28, 118, 137: the detection boxes held one side of the flight;
	// its labelled cells run on beyond them.
	auto whole = floorFan(3.0);
	for (double x = 2.0; x <= 3.2; x += 0.03)
		for (double y = -0.6; y <= 0.6; y += 0.03)
			whole.push_back({x, y, 0.2 + 0.3 * (x - 2.0), Label::Stairs});
	EXPECT_LT(offCentre(cornerDetected(whole, 1.0, 0)), 0.08);
	EXPECT_GT(offCentre(cornerDetected(whole, 0, 0)), 0.3) << "rule off";
	// indoor_78, 153: from the foot of a flight its upper treads are
	// hidden; its risers, 0.25-0.3 m apart, are separate rows of cells.
	EXPECT_LT(offCentre(cornerDetected(risers(), 1.0, 0.35)), 0.08);
	EXPECT_GT(offCentre(cornerDetected(risers(), 1.0, 0)), 0.3)
	    << "the first riser only";
}

TEST(SemanticMap, AFlightsRisersConnectAcrossTheirRun)
{
	// indoor_78, 109, 153: seen from its foot, a flight's risers are rows
	// of cells a run apart; a chair in front of it that a false detection
	// labelled stairs is no riser.
	SemanticMap::TOptions o;
	o.stairsCellMargin = 1.0;
	o.stairsRiserGap = 0.4;
	o.stairsRiserMinRow = 0.5;
	EXPECT_LT(offCentre(cornerDetected(risers(), o)), 0.08);
	auto off = o;
	off.stairsRiserGap = 0;
	EXPECT_GT(offCentre(cornerDetected(risers(), off)), 0.3)
	    << "the first riser only";
	auto withChair = risers();
	for (const double x : {1.55, 1.75})
		for (const double y : {-0.2, 0.2})
			for (double z = 0.02; z < 0.45; z += 0.05)
				for (const double d : {0.0, 0.03})
					withChair.push_back({x + d, y + d, z, Label::Stairs});
	EXPECT_LT(offCentre(cornerDetected(withChair, o)), 0.08);
	auto anyRow = o;
	anyRow.stairsRiserMinRow = 0;
	EXPECT_GT(offCentre(cornerDetected(withChair, anyRow)), 0.15)
	    << "the chair's legs taken for risers";
}

TEST(SemanticMap, SureStairsMayStartAboveTheFloor)
{
	// indoor_49, 100, 120, 130: flights detected with shape scores
	// 0.95-1 whose boxes came down to 0.11-0.17 m only.
	ObjectInstance o;
	o.label = Label::Stairs;
	o.centroid = {2, 0, 0.4};
	o.minCorner = {1.5, -0.6, 0.15};
	o.maxCorner = {2.5, 0.6, 0.7};
	o.sightings = {o.centroid, o.centroid};
	o.sightingSizes = {{1.2, 0, 0.55}, {1.2, 0, 0.55}};
	o.observations = 2;
	o.views = 2;
	o.bestShapeScore = 1.0;
	SemanticMap::TOptions opts, off;
	opts.sureStairsMaxBottom = 0.2;
	off.sureStairsMaxBottom = 0;
	EXPECT_TRUE(SemanticMap(opts).reported(o));
	EXPECT_FALSE(SemanticMap(off).reported(o)) << "rule off";
	// A doubtful one (a table top) must still come down to 0.1 m.
	auto doubtful = o;
	doubtful.bestShapeScore = 0.9;
	EXPECT_FALSE(SemanticMap(opts).reported(doubtful));
	// Higher than 0.2 m: not even a sure one.
	auto high = o;
	high.minCorner.z = 0.25;
	EXPECT_FALSE(SemanticMap(opts).reported(high));
}
