/* semnav: semantic navigation from tilting-laser sweeps */
// Localizer on synthetic wall observations in a known room: tracking with
// biased odometry (main directions on / off), KLD sample size, options.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/math/wrap2pi.h>
#include <semnav/common/ConfigChecks.h>
#include <semnav/common/Error.h>
#include <semnav/localization/Localizer.h>
#include <semnav/localization/MainDirections.h>
#include <semnav/localization/MappingLocalizer.h>
#include <semnav/localization/TrajectoryError.h>

#include "LocalizationTestUtils.h"

using namespace semnav;
using mrpt::DEG2RAD;

namespace
{
/** Drives a loop in the room with odometry whose heading drifts 3.5 deg per
 * metre; returns the tracking error. */
TrajectoryError track(Localizer::TOptions o, bool mainDirections)
{
	o.mainDirections = mainDirections;
	WallMap map;
	map.addSegments(test::roomWalls());
	map.rebuild();
	Localizer loc(o);
	loc.setWallMap(&map);
	const std::vector<mrpt::poses::CPose2D> truth = {
	    {1.5, 1.0, 0},
	    {2.5, 1.2, DEG2RAD(10)},
	    {3.6, 1.5, DEG2RAD(20)},
	    {4.6, 1.8, 0},
	    {5.0, 3.0, DEG2RAD(90)},
	    {6.2, 3.4, 0},
	    {7.4, 3.1, DEG2RAD(-30)},
	    {8.4, 2.0, DEG2RAD(-60)},
	    {8.8, 1.0, DEG2RAD(-90)},
	    {7.8, 0.8, DEG2RAD(180)},
	    {7.5, 1.8, DEG2RAD(100)}};
	loc.initialize(truth[0]);
	mrpt::poses::CPose2D odo = truth[0];
	TrajectoryError err;
	for (std::size_t i = 1; i < truth.size(); i++)
	{
		mrpt::poses::CPose2D incr = truth[i] - truth[i - 1];
		const double dist = incr.norm();
		incr.phi(incr.phi() + DEG2RAD(3.5) * dist);  // heading bias
		odo = odo + incr;
		const auto u =
		    loc.update(incr, test::observe(test::roomWalls(), truth[i]));
		err.add(u.pose, truth[i]);
	}
	TrajectoryError odoErr;
	odoErr.add(odo, truth.back());
	EXPECT_GT(odoErr.finalYaw(), DEG2RAD(25));
	return err;
}
}  // namespace

TEST(Localizer, TracksBiasedOdometryWithMainDirections)
{
	const auto on = track(Localizer::TOptions(), true);
	EXPECT_LT(on.finalYaw(), DEG2RAD(1));
	EXPECT_LT(on.maxYaw(), DEG2RAD(1.5));
	EXPECT_LT(on.rmseXY(), 0.05);
	const auto off = track(Localizer::TOptions(), false);
	EXPECT_LT(off.rmseXY(), 0.15);
	EXPECT_GT(off.maxYaw(), on.maxYaw());
}

TEST(Localizer, KldAdaptsTheSampleSize)
{
	Localizer::TOptions o;
	o.kldMinSamples = 100;
	WallMap map;
	map.addSegments(test::roomWalls());
	map.rebuild();
	Localizer loc(o);
	loc.setWallMap(&map);
	const mrpt::poses::CPose2D p(3, 2, 0);
	loc.initialize(p);
	// Prediction only over 5 m: the cloud spreads and KLD adds particles.
	const WallObservation none;
	LocalizationUpdate u;
	for (int i = 0; i < 5; i++)
		u = loc.update(mrpt::poses::CPose2D(1, 0, 0), none);
	const std::size_t spread = u.particles;
	EXPECT_FALSE(u.converged);
	// Observations concentrate it again: fewer particles.
	const mrpt::poses::CPose2D q(5.5, 2.2, DEG2RAD(5));
	loc.initialize(q);
	for (int i = 0; i < 3; i++)
		u = loc.update(
		    mrpt::poses::CPose2D(), test::observe(test::roomWalls(), q));
	EXPECT_TRUE(u.converged);
	EXPECT_LT(u.particles, spread / 2);
	EXPECT_GE(u.particles, 100u);
	EXPECT_LT((u.pose.translation() - q.translation()).norm(), 0.05);
}

TEST(Localizer, GlobalStartNeedsAKnownMap)
{
	Localizer loc;
	EXPECT_THROW(loc.initializeGlobal(), Error);
}

TEST(Localizer, ShippedConfigLoadsAndRoundTrips)
{
	const auto cfg = openIniFile(
	    std::string(SEMNAV_SOURCE_DIR) + "/config/localization.ini",
	    MappingLocalizer::TOptions::sections());
	MappingLocalizer::TOptions o;
	o.loadFromConfigFile(*cfg, "");
	EXPECT_TRUE(o.localizer.mainDirections);
	EXPECT_EQ(o.localizer.particles, Localizer::TOptions().particles);
	EXPECT_DOUBLE_EQ(o.wallMap.sigma, WallMap::TOptions().sigma);
	EXPECT_DOUBLE_EQ(o.walls.minLength, WallExtractor::TOptions().minLength);
	mrpt::config::CConfigFileMemory mem;
	o.saveToConfigFile(mem, "");
	MappingLocalizer::TOptions back;
	back.localizer.mainDirections = false;
	back.loadFromConfigFile(mem, "");
	EXPECT_TRUE(back.localizer.mainDirections);
	EXPECT_NEAR(back.localizer.kldBinYaw, o.localizer.kldBinYaw, 1e-12);
}

TEST(Localizer, OptionsRejectUnknownKeysAndOutOfRangeValues)
{
	Localizer::TOptions o;
	mrpt::config::CConfigFileMemory a;
	a.write("Localizer", "main_direction", "false");
	EXPECT_THROW(o.loadFromConfigFile(a, "Localizer"), ConfigError);
	mrpt::config::CConfigFileMemory b;
	b.write("Localizer", "ess_threshold", 1.5);
	EXPECT_THROW(o.loadFromConfigFile(b, "Localizer"), ConfigError);
	mrpt::config::CConfigFileMemory c;
	c.write("Localizer", "kld_min_samples", 500);
	c.write("Localizer", "kld_max_samples", 100);
	EXPECT_THROW(o.loadFromConfigFile(c, "Localizer"), ConfigError);
	mrpt::config::CConfigFileMemory d;
	d.write("WallMap", "sigma_m", 0);
	WallMap::TOptions w;
	EXPECT_THROW(w.loadFromConfigFile(d, "WallMap"), ConfigError);
}

TEST(WallMonteCarlo2D, PropagationSnapsHeadingsToTheMainDirection)
{
	WallMonteCarlo2D pdf(1);
	pdf.seed(5);
	// Map walls at 3 deg; the sweep sees its walls at -27 deg: the robot's
	// yaw is 30 deg (mod 90).
	pdf.setHeadingCorrection(
	    DEG2RAD(3), DEG2RAD(-27), DEG2RAD(0.5), DEG2RAD(45));
	for (double yaw : {30.0, 10.0, 48.0, -55.0, 121.0})
	{
		mrpt::math::TPose2D p;
		pdf.PF_SLAM_implementation_custom_update_particle_with_new_pose(
		    &p, mrpt::math::TPose3D(1, 2, 0, DEG2RAD(yaw), 0, 0));
		EXPECT_DOUBLE_EQ(p.x, 1);
		EXPECT_DOUBLE_EQ(p.y, 2);
		const double expected =
		    yaw + MainDirections::wrapQuarter(DEG2RAD(30 - yaw)) / M_PI * 180;
		EXPECT_NEAR(
		    mrpt::math::wrapToPi(p.phi - DEG2RAD(expected)), 0, DEG2RAD(2.5))
		    << yaw;
		EXPECT_NEAR(
		    MainDirections::wrapQuarter(p.phi - DEG2RAD(30)), 0, DEG2RAD(2.5));
	}
	// Without a direction the heading is kept.
	pdf.setHeadingCorrection(std::nullopt, DEG2RAD(-27), 0, DEG2RAD(45));
	mrpt::math::TPose2D p;
	pdf.PF_SLAM_implementation_custom_update_particle_with_new_pose(
	    &p, mrpt::math::TPose3D(0, 0, 0, DEG2RAD(48), 0, 0));
	EXPECT_DOUBLE_EQ(p.phi, DEG2RAD(48));
	// Corrections larger than max_correction are not applied.
	pdf.setHeadingCorrection(DEG2RAD(3), DEG2RAD(-27), 0, DEG2RAD(10));
	pdf.PF_SLAM_implementation_custom_update_particle_with_new_pose(
	    &p, mrpt::math::TPose3D(0, 0, 0, DEG2RAD(48), 0, 0));
	EXPECT_DOUBLE_EQ(p.phi, DEG2RAD(48));
}
