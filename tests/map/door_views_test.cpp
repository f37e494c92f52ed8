/* semnav: semantic navigation from tilting-laser sweeps */
// Door views and the door detection ratio (SemanticMap::TOptions::
// doorMinDetectionRatio; docs/mapping.md, "Objects in the map").
#include <gtest/gtest.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/map/SweepView.h>
#include <semnav/scan/TiltGeometry.h>

#include <vector>

#include "MapTestUtils.h"

using namespace semnav;

namespace
{
/** A sweep of a wall `wallRange` m away everywhere (tilts -0.3..0.6 rad,
 * bearings -1.2..1.2 rad, 0.01 rad steps), sensor 0.45 m up; pixels at a
 * bearing above `occluderPhi` (rad) return at 1 m instead (a cupboard on the
 * left). */
Sweep wallSweep(double wallRange, double occluderPhi = 10)
{
	std::vector<double> thetas, phis;
	for (double t = -0.3; t <= 0.6 + 1e-9; t += 0.01) thetas.push_back(t);
	for (double p = -1.2; p <= 1.2 + 1e-9; p += 0.01) phis.push_back(p);
	Sweep s(thetas.size(), phis.size());
	for (std::size_t r = 0; r < thetas.size(); r++)
		s.setRow(r, thetas[r], tiltedSensorPose({0, 0, 0.45}, thetas[r]));
	s.setPhis(phis);
	s.setMaxRange(30);
	for (std::size_t r = 0; r < thetas.size(); r++)
		for (std::size_t c = 0; c < phis.size(); c++)
			s.setRange(
			    r, c,
			    static_cast<float>(phis[c] > occluderPhi ? 1.0 : wallRange),
			    true);
	return s;
}

/** The classified sweep with a door region at (3, 0, 1) in the robot frame
 * (0.9 m wide, 2 m high, facing `normal`), or without. */
LabeledSweep labelled(
    bool door, const mrpt::math::TPoint3D& normal = {-1, 0, 0})
{
	auto f = test::makeFakeSweep(test::floorFan(2.5));
	if (door)
	{
		LabeledRegion reg;
		reg.id = 0;
		reg.label = Label::Door;
		reg.imageBox = cv::Rect(0, 0, 1, 1);
		reg.centroid = {3.0, 0.0, 1.0};
		reg.minCorner = {2.95, -0.45, 0.0};
		reg.maxCorner = {3.05, 0.45, 2.0};
		reg.width = 0.9;
		reg.height = 2.0;
		reg.meanNormal = normal;
		f.labeled.regions = {reg};
	}
	return f.labeled;
}

/** Maps five sweeps from the origin, a door region in those `detected`
 * says; returns the door candidates. */
std::vector<ObjectInstance> mapDoor(
    const SemanticMap::TOptions& o, const std::vector<bool>& detected,
    const Sweep& sweep, std::vector<ObjectInstance>* reported = nullptr,
    const mrpt::math::TPoint3D& normal = {-1, 0, 0})
{
	SemanticMap m(o);
	for (bool d : detected)
		m.insert(sweep, labelled(d, normal), mrpt::poses::CPose2D(0, 0, 0));
	if (reported) *reported = m.instances(Label::Door);
	return m.allInstances();
}
}  // namespace

TEST(SweepView, VisibleShareOfADoorHalfBehindACupboard)
{
	const mrpt::math::TPoint3D door{3.0, 0.0, 1.0}, size{0.9, 0, 2.0};
	const double bearing = 80 * M_PI / 180;
	EXPECT_DOUBLE_EQ(
	    SweepView(wallSweep(6), bearing, 150).visibleShare(door, size), 1.0);
	// The cupboard hides the door's left third (y > 0: bearings > 0.05).
	EXPECT_NEAR(
	    SweepView(wallSweep(6, 0.05), bearing, 150).visibleShare(door, size),
	    6.0 / 9, 1e-9);
	// A wall in front of all of it, or the door out of the bearing.
	EXPECT_DOUBLE_EQ(
	    SweepView(wallSweep(1.5), bearing, 150).visibleShare(door, size), 0.0);
	EXPECT_DOUBLE_EQ(
	    SweepView(wallSweep(6), bearing, 150)
	        .visibleShare({0.3, 3.0, 1.0}, size),
	    0.0);
}

TEST(SemanticMap, ADoorDetectedOnceInManyViewsIsNotReported)
{
	SemanticMap::TOptions o;
	o.doorMinDetectionRatio = 0.25;
	o.doorViewHistory = 30;
	const Sweep open = wallSweep(6);
	std::vector<ObjectInstance> rep;
	// Detected in the middle of five sweeps that all had it in view: the
	// views before its first detection count too.
	auto all = mapDoor(o, {false, false, true, false, false}, open, &rep);
	ASSERT_EQ(all.size(), 1u);
	EXPECT_EQ(all[0].observations, 1u);
	EXPECT_EQ(all[0].views, 5u);
	EXPECT_TRUE(rep.empty()) << "1 of 5 views is below 0.25";
	// Detected in two of five: reported.
	all = mapDoor(o, {false, true, false, true, false}, open, &rep);
	ASSERT_EQ(all.size(), 1u);
	EXPECT_EQ(all[0].observations, 2u);
	EXPECT_EQ(all[0].views, 5u);
	EXPECT_EQ(rep.size(), 1u);
	// The other sweeps had a wall in front of its place: its only view.
	SemanticMap m(o);
	m.insert(open, labelled(true), mrpt::poses::CPose2D(0, 0, 0));
	for (int k = 0; k < 4; k++)
		m.insert(
		    wallSweep(1.5), labelled(false), mrpt::poses::CPose2D(0, 0, 0));
	ASSERT_EQ(m.allInstances().size(), 1u);
	EXPECT_EQ(m.allInstances()[0].views, 1u);
	EXPECT_EQ(m.instances(Label::Door).size(), 1u);
	// Seen edge-on (its normal across the line of sight, as a door along
	// a corridor): beyond doorViewMaxIncidenceDeg, no view but the
	// detection.
	all = mapDoor(o, {false, false, true, false, false}, open, &rep, {0, 1, 0});
	EXPECT_EQ(all[0].views, 1u);
	EXPECT_EQ(rep.size(), 1u);
	// No history: only the views from its first detection on count.
	o.doorViewHistory = 0;
	all = mapDoor(o, {false, false, false, false, true}, open, &rep);
	EXPECT_EQ(all[0].views, 1u);
	EXPECT_EQ(rep.size(), 1u);
	// Ratio 0: no check.
	o.doorViewHistory = 30;
	o.doorMinDetectionRatio = 0;
	mapDoor(o, {true, false, false, false, false, false}, open, &rep);
	EXPECT_EQ(rep.size(), 1u);
}
