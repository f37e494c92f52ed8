/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/serialization/CArchive.h>
#include <semnav/common/ConfigChecks.h>
#include <semnav/common/Error.h>
#include <semnav/scan/TiltGeometry.h>
#include <semnav/sim/OdometrySimulator.h>
#include <semnav/sim/RayCaster.h>
#include <semnav/sim/SimulationRunner.h>
#include <semnav/sim/TiltingLaserSimulator.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <random>
#include <sstream>

#include "../common/SavedAndLoaded.h"

using namespace semnav;
using mrpt::math::TPoint3D;
using mrpt::math::TPose2D;
namespace fs = std::filesystem;

namespace
{
constexpr double kDegree = M_PI / 180;

/** Room [-4, 4]^2, ceiling 2.5 m, one wall (id 1) whose face is x = 3. */
Scene room()
{
	Scene s;
	s.name = "room";
	s.bounds = {-4, -4, 4, 4};
	s.ceilingHeight = 2.5;
	SceneObject wall;
	wall.label = Label::Wall;
	wall.id = 1;
	wall.parts.push_back(BoxShape{{3.05, 0, 1.25}, {0.1, 8, 2.5}, 0});
	s.objects.push_back(wall);
	return s;
}

/** 22 lines x 37 beams (5 deg steps). */
SensorSpec smallSpec()
{
	SensorSpec sp;
	sp.phiStep = 5 * kDegree;
	sp.thetaStep = 5 * kDegree;
	return sp;
}

struct Analytic
{
	double range = -1;  // < 0: no hit
	Label label = Label::Unknown;
	double gap = 1e9;  // distance to the second-nearest surface
};

/** Independent model of room(): planes z = 0, z = 2.5, x = 3. */
Analytic analyticRoom(const TPoint3D& o, const TPoint3D& d)
{
	Analytic a;
	auto offer = [&](double t, Label l)
	{
		if (a.range < 0 || t < a.range)
		{
			if (a.range >= 0) a.gap = a.range - t;
			a.range = t;
			a.label = l;
		}
		else
			a.gap = std::min(a.gap, t - a.range);
	};
	auto inBounds = [](double x, double y)
	{ return std::abs(x) <= 4 && std::abs(y) <= 4; };
	if (d.z < 0)
	{
		const double t = -o.z / d.z;
		if (inBounds(o.x + t * d.x, o.y + t * d.y)) offer(t, Label::Floor);
	}
	if (d.z > 0)
	{
		const double t = (2.5 - o.z) / d.z;
		if (inBounds(o.x + t * d.x, o.y + t * d.y)) offer(t, Label::Ceiling);
	}
	if (d.x > 0)
	{
		const double t = (3 - o.x) / d.x;
		const double y = o.y + t * d.y, z = o.z + t * d.z;
		if (std::abs(y) <= 4 && z >= 0 && z <= 2.5) offer(t, Label::Wall);
	}
	return a;
}

/** Reads every object of a rawlog. */
std::vector<mrpt::serialization::CSerializable::Ptr> readRawlog(
    const std::string& path)
{
	std::vector<mrpt::serialization::CSerializable::Ptr> out;
	mrpt::io::CFileGZInputStream f(path);
	auto arch = mrpt::serialization::archiveFrom(f);
	for (;;)
	{
		try
		{
			out.push_back(arch.ReadObject());
		}
		catch (const mrpt::serialization::CExceptionEOF&)
		{
			break;
		}
	}
	return out;
}

fs::path tempDir(const std::string& name)
{
	const fs::path p =
	    fs::temp_directory_path() /
	    ("semnav_sim_test_" + name + "_" + std::to_string(::getpid()));
	fs::remove_all(p);
	return p;
}
}  // namespace

TEST(TiltingLaserSimulator, SweepGeometryAndRanges)
{
	const Scene s = room();
	SensorSpec spec;  // the paper's: 211 x 361
	spec.rangeNoise = 0.01;
	spec.maxRange = 6.0;
	const RayCaster rc(s);
	const TiltingLaserSimulator sim(rc, spec, 42);
	ASSERT_EQ(sim.lineCount(), 211u);
	ASSERT_EQ(sim.beamCount(), 361u);
	const TPose2D pose(1.0, -0.5, 20 * kDegree);
	const auto t0 = SimulationRunner::epoch();
	const double period = 1 / 37.5;
	const SimulatedSweep sw = sim.simulate(pose, 0, t0, period);

	ASSERT_EQ(sw.lines.size(), 211u);
	ASSERT_EQ(sw.labels.rows, 211);
	ASSERT_EQ(sw.labels.cols, 361);
	ASSERT_EQ(sw.labels.type(), CV_16UC1);
	EXPECT_TRUE(sw.ascending);

	const double cy = std::cos(pose.phi), sy = std::sin(pose.phi);
	const TPoint3D o(
	    pose.x + cy * spec.mount.x - sy * spec.mount.y,
	    pose.y + sy * spec.mount.x + cy * spec.mount.y, spec.mount.z);
	double sum = 0, sum2 = 0;
	std::size_t n = 0, invalidChecked = 0, labelChecked = 0;
	for (std::size_t r = 0; r < 211; r++)
	{
		const auto& line = sw.lines[r];
		const double theta = spec.thetaMin + r * spec.thetaStep;
		ASSERT_EQ(line.getScanSize(), 361u);
		EXPECT_EQ(line.sensorLabel, "TILT_LMS");
		EXPECT_TRUE(line.rightToLeft);
		EXPECT_NEAR(line.aperture, M_PI, 1e-6);
		EXPECT_FLOAT_EQ(line.maxRange, 6.0f);
		EXPECT_FLOAT_EQ(line.stdError, 0.01f);
		EXPECT_NEAR(tiltOfSensorPose(line.sensorPose), theta, 1e-9);
		EXPECT_NEAR(
		    std::chrono::duration<double>(line.timestamp - t0).count(),
		    r * period, 1e-7);
		for (std::size_t c = 0; c < 361; c++)
		{
			const double phi = spec.phiMin + c * spec.phiStep;
			// Beam direction from TiltGeometry.h's formula, then to the world.
			const TPoint3D dr(
			    std::cos(phi) * std::cos(theta), std::sin(phi),
			    std::cos(phi) * std::sin(theta));
			const TPoint3D d(
			    cy * dr.x - sy * dr.y, sy * dr.x + cy * dr.y, dr.z);
			if (r % 30 == 0 && c % 60 == 0)
			{
				// MRPT's own beam layout on the stored sensorPose agrees.
				const double b = -line.aperture / 2 + c * line.aperture / 360.0;
				const auto& R = line.sensorPose.getRotationMatrix();
				EXPECT_NEAR(
				    R(0, 0) * std::cos(b) + R(0, 1) * std::sin(b), dr.x, 1e-6);
				EXPECT_NEAR(
				    R(1, 0) * std::cos(b) + R(1, 1) * std::sin(b), dr.y, 1e-6);
				EXPECT_NEAR(
				    R(2, 0) * std::cos(b) + R(2, 1) * std::sin(b), dr.z, 1e-6);
			}
			const Analytic a = analyticRoom(o, d);
			const bool valid = line.getScanRangeValidity(c);
			const uint16_t lab = sw.labels.at<uint16_t>(
			    static_cast<int>(r), static_cast<int>(c));
			EXPECT_EQ(valid, lab != 0);
			if (a.range < 0 || a.range > spec.maxRange + 0.06)
			{
				EXPECT_FALSE(valid) << r << " " << c;
				EXPECT_FLOAT_EQ(line.getScanRange(c), 6.0f);
				invalidChecked++;
				continue;
			}
			if (a.range > spec.maxRange - 0.06) continue;
			ASSERT_TRUE(valid) << r << " " << c;
			const double res = line.getScanRange(c) - a.range;
			sum += res;
			sum2 += res * res;
			n++;
			EXPECT_NEAR(
			    sw.trueRanges.at<float>(
			        static_cast<int>(r), static_cast<int>(c)),
			    a.range, 1e-5);
			if (a.gap > 0.01)
			{
				const int inst = a.label == Label::Wall ? 1 : 0;
				EXPECT_EQ(lab, static_cast<unsigned>(a.label) | (inst << 8))
				    << r << " " << c;
				labelChecked++;
			}
		}
	}
	ASSERT_GT(n, 50000u);
	EXPECT_GT(invalidChecked, 500u);
	EXPECT_GT(labelChecked, 50000u);
	const double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
	EXPECT_NEAR(mean, 0.0, 4 * 0.01 / std::sqrt(double(n)));
	EXPECT_NEAR(sd, 0.01, 0.0005);

	// Row 0 (lowest tilt) at phi = 0 looks down: floor; the top row
	// (theta = 90 deg) sees the ceiling; theta = 0 at phi = -20 deg, i.e.
	// straight along world x, sees the wall.
	EXPECT_EQ(
	    sw.labels.at<uint16_t>(0, 180), static_cast<uint16_t>(Label::Floor));
	EXPECT_EQ(
	    sw.labels.at<uint16_t>(210, 180),
	    static_cast<uint16_t>(Label::Ceiling));
	EXPECT_EQ(
	    sw.labels.at<uint16_t>(30, 140),
	    static_cast<uint16_t>(Label::Wall) | (1 << 8));
}

TEST(TiltingLaserSimulator, AscendingAndDescendingAlternate)
{
	const Scene s = room();
	const SensorSpec spec = smallSpec();
	const RayCaster rc(s);
	const TiltingLaserSimulator sim(rc, spec, 1);
	const std::size_t nl = sim.lineCount();
	ASSERT_EQ(nl, 22u);
	ASSERT_EQ(sim.beamCount(), 37u);
	const auto t0 = SimulationRunner::epoch();
	const SimulatedSweep up = sim.simulate({0, 0, 0}, 0, t0, 0.1);
	const SimulatedSweep down = sim.simulate({0, 0, 0}, 1, t0, 0.1);
	const SimulatedSweep up2 = sim.simulate({0, 0, 0}, 2, t0, 0.1);
	EXPECT_TRUE(up.ascending);
	EXPECT_FALSE(down.ascending);
	EXPECT_TRUE(up2.ascending);
	for (std::size_t i = 0; i < nl; i++)
	{
		EXPECT_NEAR(
		    tiltOfSensorPose(up.lines[i].sensorPose),
		    spec.thetaMin + i * spec.thetaStep, 1e-9);
		EXPECT_NEAR(
		    tiltOfSensorPose(up2.lines[i].sensorPose),
		    spec.thetaMin + i * spec.thetaStep, 1e-9);
		EXPECT_NEAR(
		    tiltOfSensorPose(down.lines[i].sensorPose),
		    spec.thetaMin + (nl - 1 - i) * spec.thetaStep, 1e-9);
	}
	// Both ends included: the first descending line repeats the last
	// ascending tilt.
	EXPECT_NEAR(
	    tiltOfSensorPose(down.lines.front().sensorPose), spec.thetaMax, 1e-9);
	EXPECT_NEAR(
	    tiltOfSensorPose(up.lines.back().sensorPose), spec.thetaMax, 1e-9);
	// Label rows stay ordered by tilt: same geometry, same labels.
	const cv::Mat diff = up.labels != down.labels;
	EXPECT_LT(cv::countNonZero(diff), static_cast<int>(nl * 37 / 100));
	EXPECT_EQ(
	    down.labels.at<uint16_t>(0, 18), static_cast<uint16_t>(Label::Floor));
	EXPECT_EQ(
	    down.labels.at<uint16_t>(static_cast<int>(nl) - 1, 18),
	    static_cast<uint16_t>(Label::Ceiling));
	// The organized Sweep keeps the same order.
	const Sweep sd = down.toSweep();
	ASSERT_EQ(sd.rows(), nl);
	ASSERT_EQ(sd.cols(), 37u);
	EXPECT_FALSE(sd.quality().ascending);
	EXPECT_NEAR(sd.theta(0), spec.thetaMin, 1e-12);
	EXPECT_NEAR(sd.phi(0), -M_PI / 2, 1e-12);
	for (std::size_t r = 0; r < nl; r++)
		for (std::size_t c = 0; c < 37; c++)
		{
			EXPECT_EQ(
			    sd.valid(r, c), down.labels.at<uint16_t>(int(r), int(c)) != 0);
			EXPECT_EQ(sd.range(r, c), down.lines[nl - 1 - r].getScanRange(c));
		}
}

TEST(TiltingLaserSimulator, Deterministic)
{
	Scene s = room();
	SceneObject grass;
	grass.label = Label::Grass;
	grass.id = 2;
	grass.parts.push_back(TerrainShape{
	    {{-3.5, -3.5}, {2.9, -3.5}, {2.9, 3.5}, {-3.5, 3.5}}, 0.05});
	s.objects.push_back(grass);
	const SensorSpec spec = smallSpec();
	const RayCaster rc(s, 9);
	TiltingLaserSimulator a(rc, spec, 5), b(rc, spec, 5), c(rc, spec, 6);
	a.setThreads(1);
	b.setThreads(2);
	const auto t0 = SimulationRunner::epoch();
	const TPose2D pose(0.5, 0.2, 0.3);
	const auto sa = a.simulate(pose, 3, t0, 0.1);
	const auto sb = b.simulate(pose, 3, t0, 0.1);
	const auto sc = c.simulate(pose, 3, t0, 0.1);
	const auto sa4 = a.simulate(pose, 4, t0, 0.1);
	std::size_t differ = 0, differSweep = 0;
	for (std::size_t i = 0; i < sa.lines.size(); i++)
		for (std::size_t k = 0; k < 37; k++)
		{
			ASSERT_EQ(sa.lines[i].getScanRange(k), sb.lines[i].getScanRange(k));
			ASSERT_EQ(
			    sa.lines[i].getScanRangeValidity(k),
			    sb.lines[i].getScanRangeValidity(k));
			if (sa.lines[i].getScanRange(k) != sc.lines[i].getScanRange(k))
				differ++;
			// Sweep 4 ascends, sweep 3 descends: compare the same tilt.
			if (sa.lines[i].getScanRange(k) !=
			    sa4.lines[sa.lines.size() - 1 - i].getScanRange(k))
				differSweep++;
		}
	EXPECT_EQ(cv::countNonZero(sa.labels != sb.labels), 0);
	EXPECT_GT(differ, sa.lines.size() * 37 / 2);
	EXPECT_GT(differSweep, sa.lines.size() * 37 / 2);
	// Terrain was hit.
	EXPECT_GT(
	    cv::countNonZero(
	        sa.labels == (static_cast<int>(Label::Grass) | (2 << 8))),
	    20);
}

TEST(OdometrySimulator, StartsAtFirstPoseAndIsExactWithoutNoise)
{
	OdometrySpec none;
	none.transNoise = none.rotNoisePerM = none.rotBiasPerM = 0;
	const std::vector<TPose2D> traj{
	    {1, 2, 0.1}, {3, 2.5, 0.4}, {3, 5, 2.0}, {-1, 4, -2.5}};
	const auto odo = OdometrySimulator::simulate(none, traj, 3);
	ASSERT_EQ(odo.size(), traj.size());
	for (std::size_t i = 0; i < traj.size(); i++)
	{
		EXPECT_NEAR(odo[i].x(), traj[i].x, 1e-9);
		EXPECT_NEAR(odo[i].y(), traj[i].y, 1e-9);
		EXPECT_NEAR(mrpt::math::wrapToPi(odo[i].phi() - traj[i].phi), 0, 1e-9);
	}
	const auto noisy = OdometrySimulator::simulate(OdometrySpec{}, traj, 3);
	EXPECT_EQ(noisy[0].x(), traj[0].x);
	EXPECT_EQ(noisy[0].phi(), traj[0].phi);
	EXPECT_GT(std::abs(noisy.back().x() - traj.back().x), 1e-6);
}

TEST(OdometrySimulator, NoiseStatistics)
{
	OdometrySpec spec;
	spec.transNoise = 0.02;
	spec.rotNoisePerM = 2 * kDegree;
	spec.rotBiasPerM = 1 * kDegree;
	const int trials = 4000;
	const double s = 2.0;
	double sh = 0, sh2 = 0, sx2 = 0, sy2 = 0;
	double sh10 = 0, sh10sq = 0;
	for (int k = 0; k < trials; k++)
	{
		OdometrySimulator sim(spec, {0, 0, 0}, k);
		const auto& p = sim.move({0, 0, 0}, {s, 0, 0});
		const double e = mrpt::math::wrapToPi(p.phi());
		sh += e;
		sh2 += e * e;
		sx2 += (p.x() - s) * (p.x() - s);
		sy2 += p.y() * p.y();
		// Ten 1 m steps: errors add up.
		OdometrySimulator sim10(spec, {0, 0, 0}, 100000 + k);
		for (int j = 0; j < 10; j++)
			sim10.move({double(j), 0, 0}, {double(j + 1), 0, 0});
		const double e10 = mrpt::math::wrapToPi(sim10.odometry().phi());
		sh10 += e10;
		sh10sq += e10 * e10;
	}
	const double mean = sh / trials, sd = std::sqrt(sh2 / trials - mean * mean);
	EXPECT_NEAR(
	    mean, spec.rotBiasPerM * s,
	    4 * spec.rotNoisePerM * s / std::sqrt(trials));
	EXPECT_NEAR(sd, spec.rotNoisePerM * s, 0.07 * spec.rotNoisePerM * s);
	EXPECT_NEAR(
	    std::sqrt(sx2 / trials), spec.transNoise * s,
	    0.07 * spec.transNoise * s);
	EXPECT_NEAR(
	    std::sqrt(sy2 / trials), spec.transNoise * s,
	    0.07 * spec.transNoise * s);
	const double mean10 = sh10 / trials,
	             sd10 = std::sqrt(sh10sq / trials - mean10 * mean10);
	EXPECT_NEAR(
	    mean10, spec.rotBiasPerM * 10,
	    4 * spec.rotNoisePerM * std::sqrt(10.0) / std::sqrt(trials));
	EXPECT_NEAR(
	    sd10, spec.rotNoisePerM * std::sqrt(10.0),
	    0.07 * spec.rotNoisePerM * std::sqrt(10.0));
}

TEST(OdometrySimulator, BiasOfThreeAndAHalfDegPerMetreOverTenMetres)
{
	std::vector<TPose2D> traj;
	for (int i = 0; i <= 10; i++) traj.emplace_back(i, 0, 0);
	OdometrySpec spec;
	spec.rotBiasPerM = 3.5 * kDegree;
	spec.rotNoisePerM = 0;
	spec.transNoise = 0;
	const auto odo = OdometrySimulator::simulate(spec, traj, 1);
	const double err =
	    std::abs(mrpt::math::wrapToPi(odo.back().phi() - traj.back().phi));
	EXPECT_GT(err, 30 * kDegree);
	EXPECT_NEAR(err, 35 * kDegree, 1e-9);
	// With the default heading noise on top, the mean error stays > 30 deg.
	spec.rotNoisePerM = OdometrySpec{}.rotNoisePerM;
	spec.transNoise = OdometrySpec{}.transNoise;
	double sum = 0;
	for (int k = 0; k < 200; k++)
		sum += mrpt::math::wrapToPi(
		    OdometrySimulator::simulate(spec, traj, k).back().phi());
	EXPECT_GT(sum / 200, 30 * kDegree);
}

TEST(SimulationRunner, WritesRawlogGroundTruthAndLabels)
{
	Scene s = room();
	s.name = "tiny";
	s.sensor = smallSpec();
	s.trajectory = {{0, 0, 0}, {1.2, 0, 0}, {1.2, 0.9, M_PI / 2}};
	SimulationRunner::TOptions opt;
	const fs::path dir = tempDir("runner");
	const SimulationRunner runner(s, opt, 77);
	std::vector<std::size_t> progress;
	const SimulationResult res = runner.run(
	    dir.string(),
	    [&](std::size_t done, std::size_t total)
	    {
		    EXPECT_EQ(total, 3u);
		    progress.push_back(done);
	    });
	EXPECT_EQ(progress, (std::vector<std::size_t>{1, 2, 3}));
	EXPECT_EQ(res.sweeps, 3u);
	EXPECT_EQ(res.scans, 3u * 22);
	EXPECT_EQ(res.odometry, 3u);
	EXPECT_EQ(fs::path(res.rawlogPath), dir / "tiny.rawlog");
	EXPECT_EQ(fs::path(res.gtPath), dir / "tiny.gt.txt");
	EXPECT_EQ(fs::path(res.labelsDir), dir / "tiny.labels");

	// Rawlog: odometry, then the 22 lines of each sweep.
	const auto objs = readRawlog(res.rawlogPath);
	ASSERT_EQ(objs.size(), 3u * 23);
	std::size_t scans = 0, odos = 0;
	std::vector<double> sweepStart;
	for (std::size_t k = 0; k < objs.size(); k++)
	{
		if (k % 23 == 0)
		{
			auto o = std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(
			    objs[k]);
			ASSERT_TRUE(o) << k;
			odos++;
			if (k == 0)
			{
				EXPECT_EQ(o->odometry.x(), 0.0);
				EXPECT_EQ(o->odometry.phi(), 0.0);
			}
			sweepStart.push_back(mrpt::Clock::toDouble(o->timestamp));
			continue;
		}
		auto sc = std::dynamic_pointer_cast<mrpt::obs::CObservation2DRangeScan>(
		    objs[k]);
		ASSERT_TRUE(sc) << k;
		EXPECT_EQ(sc->sensorLabel, "TILT_LMS");
		EXPECT_EQ(sc->getScanSize(), 37u);
		if (k % 23 == 1)
		{
			EXPECT_NEAR(
			    mrpt::Clock::toDouble(sc->timestamp), sweepStart.back(), 1e-6);
		}
		scans++;
	}
	EXPECT_EQ(scans, 66u);
	EXPECT_EQ(odos, 3u);
	// Timing: sweep, then travel (1.2 m at 0.3 m/s; 0.9 m + 90 deg at 30
	// deg/s).
	const double sweepTime = 22 * opt.linePeriod;
	EXPECT_NEAR(sweepStart[0], 1577836800.0, 1e-6);
	EXPECT_NEAR(sweepStart[1] - sweepStart[0], sweepTime + 1.2 / 0.3, 1e-5);
	EXPECT_NEAR(
	    sweepStart[2] - sweepStart[1], sweepTime + 0.9 / 0.3 + 3.0, 1e-5);

	// Ground truth.
	std::ifstream gt(res.gtPath);
	std::string line;
	std::vector<std::string> rows;
	while (std::getline(gt, line))
		if (!line.empty() && line[0] != '#') rows.push_back(line);
	ASSERT_EQ(rows.size(), 3u);
	for (std::size_t i = 0; i < 3; i++)
	{
		std::istringstream is(rows[i]);
		std::size_t idx;
		std::string ts;
		double x, y, yaw;
		is >> idx >> ts >> x >> y >> yaw;
		ASSERT_FALSE(is.fail()) << rows[i];
		EXPECT_EQ(idx, i);
		EXPECT_EQ(ts.size() - ts.find('.'), 7u) << ts;  // 6 decimals
		EXPECT_NEAR(std::stod(ts), sweepStart[i], 1e-6);
		EXPECT_NEAR(x, s.trajectory[i].x, 1e-6);
		EXPECT_NEAR(y, s.trajectory[i].y, 1e-6);
		EXPECT_NEAR(yaw, s.trajectory[i].phi, 1e-6);
	}
	EXPECT_EQ(rows[0].substr(0, 20), "0 1577836800.000000 ");

	// Label PNGs equal the simulator's, sweep by sweep.
	const RayCaster rc(s, 77, opt.terrainCell);
	const TiltingLaserSimulator sim(rc, s.sensor, 77);
	for (std::size_t i = 0; i < 3; i++)
	{
		char name[32];
		std::snprintf(name, sizeof(name), "sweep_%04zu.png", i);
		const cv::Mat img = cv::imread(
		    (dir / "tiny.labels" / name).string(), cv::IMREAD_UNCHANGED);
		ASSERT_FALSE(img.empty()) << name;
		ASSERT_EQ(img.type(), CV_16UC1);
		ASSERT_EQ(img.rows, 22);
		ASSERT_EQ(img.cols, 37);
		const auto sw =
		    sim.simulate(s.trajectory[i], i, SimulationRunner::epoch(), 0.1);
		EXPECT_EQ(cv::countNonZero(img != sw.labels), 0) << name;
		// The pixels of each object, as the label image holds them.
		ASSERT_EQ(res.objectPixels.size(), 3u);
		ASSERT_EQ(res.objectPixels[i].size(), s.objects.size() + 1);
		for (const auto& o : s.objects)
		{
			cv::Mat ids;
			img.convertTo(ids, CV_32S);
			const int n = cv::countNonZero(
			    (ids >= (o.id << 8)) & (ids < ((o.id + 1) << 8)));
			EXPECT_EQ(res.objectPixels[i][o.id], static_cast<std::size_t>(n))
			    << name << " object " << o.id;
		}
	}
	// Nothing else: no temporaries left behind.
	std::size_t files = 0;
	for (const auto& e : fs::recursive_directory_iterator(dir))
	{
		EXPECT_NE(e.path().filename().string()[0], '.') << e.path();
		files += e.is_regular_file() ? 1 : 0;
	}
	EXPECT_EQ(files, 2u + 3u);

	// Same seed, same bytes.
	const fs::path dir2 = tempDir("runner2");
	SimulationRunner::TOptions opt1 = opt;
	opt1.threads = 1;
	SimulationRunner(s, opt1, 77).run(dir2.string());
	auto slurp = [](const fs::path& p)
	{
		std::ifstream f(p, std::ios::binary);
		return std::string(std::istreambuf_iterator<char>(f), {});
	};
	EXPECT_EQ(slurp(dir / "tiny.rawlog"), slurp(dir2 / "tiny.rawlog"));
	EXPECT_EQ(slurp(dir / "tiny.gt.txt"), slurp(dir2 / "tiny.gt.txt"));
	fs::remove_all(dir);
	fs::remove_all(dir2);
}

TEST(SceneObject, CentreOfADoubleDoorIsBetweenItsLeaves)
{
	SceneObject door;
	door.label = Label::Door;
	door.parts = {
	    BoxShape{{1.0, 2.0, 1.0}, {0.5, 0.04, 2.0}, 0},
	    BoxShape{{1.6, 2.0, 1.0}, {0.5, 0.04, 2.0}, 0}};
	EXPECT_NEAR(door.centre().x, 1.3, 1e-12);
	EXPECT_NEAR(door.centre().y, 2.0, 1e-12);
	// Any other object: its first part (a washbasin's basin).
	SceneObject basin = door;
	basin.label = Label::Washbasin;
	EXPECT_NEAR(basin.centre().x, 1.0, 1e-12);
	SceneObject flight;
	flight.label = Label::Stairs;
	StairsShape st;
	st.origin = {2.0, 0.0};
	st.yaw = M_PI / 2;
	st.steps = 4;
	st.run = 0.3;
	st.width = 1.0;
	flight.parts = {st};
	EXPECT_NEAR(flight.centre().x, 2.0, 1e-12);
	EXPECT_NEAR(flight.centre().y, 0.6, 1e-12);
}

TEST(SimulationRunner, RejectsUnusableScenes)
{
	Scene s = room();
	EXPECT_THROW(SimulationRunner(s, {}, 1), SceneError);  // no trajectory
	s.trajectory = {{0, 0, 0}};
	s.name = "a/b";
	EXPECT_THROW(SimulationRunner(s, {}, 1), SceneError);
	s.name = "ok";
	EXPECT_NO_THROW(SimulationRunner(s, {}, 1));
}

TEST(SimulatorOptions, ShippedConfigHasAllKeysAtDefaults)
{
	const std::string path = std::string(SEMNAV_SOURCE_DIR) + "/config/sim.ini";
	const auto cfg = openIniFile(path, {"Simulator", "SimulatedRobot"});
	std::vector<std::string> keys;
	cfg->getAllKeys("Simulator", keys);
	EXPECT_EQ(keys.size(), SimulatorOptions::knownKeys().size());
	SimulationRunner::TOptions o;
	o.robotSpeed = 99;  // must be overwritten by the file
	o.threads = 7;
	o.loadFromConfigFile(*cfg, "Simulator");
	const SimulationRunner::TOptions d;
	EXPECT_EQ(o.sensorLabel, d.sensorLabel);
	EXPECT_NEAR(o.linePeriod, d.linePeriod, 1e-12);
	EXPECT_DOUBLE_EQ(o.robotSpeed, d.robotSpeed);
	EXPECT_NEAR(o.robotTurnRate, d.robotTurnRate, 1e-12);
	EXPECT_DOUBLE_EQ(o.terrainCell, d.terrainCell);
	EXPECT_EQ(o.threads, d.threads);
	EXPECT_EQ(o.bruteForce, d.bruteForce);
	EXPECT_EQ(o.compressLevel, d.compressLevel);
}

TEST(SimulatorOptions, SaveLoadRoundTripAndErrors)
{
	SimulationRunner::TOptions o;
	o.sensorLabel = "HEAD";
	o.linePeriod = 0.0137;
	o.robotTurnRate = 45 * kDegree;
	o.threads = 3;
	o.bruteForce = true;
	const SimulationRunner::TOptions r = test::savedAndLoaded(o, "Simulator");
	EXPECT_EQ(r.sensorLabel, "HEAD");
	EXPECT_NEAR(r.linePeriod, 0.0137, 1e-12);
	EXPECT_NEAR(r.robotTurnRate, 45 * kDegree, 1e-12);
	EXPECT_EQ(r.threads, 3);
	EXPECT_TRUE(r.bruteForce);

	auto load = [](const std::string& text)
	{
		mrpt::config::CConfigFileMemory m(text);
		SimulationRunner::TOptions t;
		t.loadFromConfigFile(m, "Simulator");
		return t;
	};
	EXPECT_NO_THROW(load("[Simulator]\nrobot_speed_mps = 0.5\n"));
	EXPECT_EQ(load("[Simulator]\nrobot_speed_mps = 0.5\n").robotSpeed, 0.5);
	EXPECT_THROW(load("[Simulator]\nrobot_sped_mps = 0.5\n"), ConfigError);
	EXPECT_THROW(load("[Simulator]\nrobot_speed_mps = -1\n"), ConfigError);
	EXPECT_THROW(load("[Simulator]\nline_period_s = 0\n"), ConfigError);
	EXPECT_THROW(load("[Simulator]\nthreads = 1.5\n"), ConfigError);
	EXPECT_THROW(load("[Simulator]\nterrain_cell_m = abc\n"), ConfigError);
	EXPECT_THROW(
	    load("[Simulator]\nbrute_force_raycast = maybe\n"), ConfigError);
	EXPECT_THROW(load("[Simulator]\nsensor_label = TWO WORDS\n"), ConfigError);
}
