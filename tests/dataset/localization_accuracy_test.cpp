/* semnav: semantic navigation from tilting-laser sweeps */
// Localization on simulated runs whose odometry heading drifts 40-55 deg:
// wall extraction against the scene, mapping with localization (main
// directions on / off, odometry, MRPT's stock MCL), global localization and
// kidnapped-robot recovery in a known map.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <semnav/common/ConfigChecks.h>
#include <semnav/localization/MainDirections.h>
#include <semnav/localization/MappingLocalizer.h>
#include <semnav/localization/TrajectoryError.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/perception/PerceptionPipeline.h>
#include <semnav/scan/GroundTruthLog.h>
#include <semnav/scan/RawlogSweepReader.h>
#include <semnav/sim/SceneLoader.h>
#include <semnav/sim/SimulationRunner.h>
#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <map>
#include <memory>

using namespace semnav;
namespace fs = std::filesystem;

namespace
{
struct SimRun
{
	Scene scene;
	std::vector<Sweep> sweeps;
	std::vector<LabeledSweep> labeled;
	std::vector<mrpt::poses::CPose2D> gt;
};

/** Simulated once per (scene, seed) and process. */
const SimRun& run(const std::string& scenePath, uint64_t seed)
{
	static std::map<std::string, std::unique_ptr<SimRun>> cache;
	const std::string key = scenePath + ":" + std::to_string(seed);
	auto& slot = cache[key];
	if (slot) return *slot;
	slot = std::make_unique<SimRun>();
	SimRun& r = *slot;
	r.scene =
	    SceneLoader::loadFile(std::string(SEMNAV_SOURCE_DIR) + "/" + scenePath);
	const fs::path dir = fs::temp_directory_path() /
	                     ("semnav_loc_" + std::to_string(::getpid()) + "_" +
	                      r.scene.name + std::to_string(seed));
	fs::remove_all(dir);
	const auto res =
	    SimulationRunner(r.scene, SimulationRunner::TOptions(), seed)
	        .run(dir.string());
	const GroundTruthLog gt(dir.string(), r.scene.name);
	r.sweeps = readRawlogSweeps(res.rawlogPath);
	PerceptionPipeline p;
	for (const auto& s : r.sweeps)
	{
		r.labeled.push_back(p.process(s));
		r.gt.push_back(gt.pose(s.index()));
	}
	fs::remove_all(dir);
	return r;
}

MappingLocalizer::TOptions shippedOptions()
{
	MappingLocalizer::TOptions o;
	o.loadFromConfigFile(
	    *openIniFile(
	        std::string(SEMNAV_SOURCE_DIR) + "/config/localization.ini",
	        MappingLocalizer::TOptions::sections()),
	    "");
	return o;
}

TrajectoryError mapRun(
    const SimRun& r, MappingLocalizer::Method method, bool mainDirections)
{
	auto o = shippedOptions();
	o.localizer.mainDirections = mainDirections;
	MappingLocalizer loc(o, method);
	SemanticMap map;
	TrajectoryError err;
	for (std::size_t i = 0; i < r.sweeps.size(); i++)
		err.add(loc.process(r.sweeps[i], r.labeled[i], map), r.gt[i]);
	return err;
}

}  // namespace

TEST(LocalizationAccuracy, StockLikelihoodPeaksAtTruePoseInTrueMap)
{
	const SimRun& r = run("datasets/office/office.yaml", 1);
	SemanticMap map;
	for (std::size_t i = 0; i < r.sweeps.size(); i++)
		map.insert(r.sweeps[i], r.labeled[i], r.gt[i]);
	auto grid = OccupancyMcl::mrptGrid(map);
	for (std::size_t i = 0; i < r.sweeps.size(); i += 3)
	{
		mrpt::obs::CSensoryFrame sf;
		sf.insert(std::make_shared<mrpt::obs::CObservation2DRangeScan>(
		    OccupancyMcl::horizontalScan(r.sweeps[i])));
		double best = -1e300;
		mrpt::poses::CPose2D arg;
		for (double dx = -0.3; dx <= 0.3; dx += 0.05)
			for (double dy = -0.3; dy <= 0.3; dy += 0.05)
				for (double da = -5; da <= 5; da += 1)
				{
					const mrpt::poses::CPose2D p(
					    r.gt[i].x() + dx, r.gt[i].y() + dy,
					    r.gt[i].phi() + mrpt::DEG2RAD(da));
					const double l = grid.computeObservationsLikelihood(
					    sf, mrpt::poses::CPose3D(p));
					if (l > best) best = l, arg = p;
				}
		EXPECT_NEAR(arg.x(), r.gt[i].x(), 0.06) << "sweep " << i;
		EXPECT_NEAR(arg.y(), r.gt[i].y(), 0.06) << "sweep " << i;
		EXPECT_NEAR(arg.phi(), r.gt[i].phi(), mrpt::DEG2RAD(1.5))
		    << "sweep " << i;
	}
}

namespace
{
/** The office mapped with true poses (seed 1): the known map. */
const SemanticMap& knownOffice()
{
	static const std::unique_ptr<SemanticMap> m = []
	{
		const SimRun& r = run("datasets/office/office.yaml", 1);
		auto map = std::make_unique<SemanticMap>();
		for (std::size_t i = 0; i < r.sweeps.size(); i++)
			map->insert(r.sweeps[i], r.labeled[i], r.gt[i]);
		return map;
	}();
	return *m;
}
}  // namespace

// Global localization over several draws of the filter: a single seed says
// little (over seeds 1-20 the office converges by the fourth update in 13 runs
// and by the fifth in the other 7), so every draw must converge by the fifth
// update and end on the true pose, and at least half by the fourth.
TEST(LocalizationAccuracy, GlobalLocalizationConvergesInKnownMap)
{
	const SimRun& r = run("datasets/office/office.yaml", 2);
	const auto o = shippedOptions();
	const WallExtractor ex(o.walls);
	constexpr int kSeeds = 8;
	int byFourthUpdate = 0;
	for (int seed = 1; seed <= kSeeds; seed++)
	{
		SCOPED_TRACE("filter seed " + std::to_string(seed));
		auto options = o.localizer;
		options.seed = seed;
		Localizer loc(options);
		loc.setKnownMap(knownOffice());
		ASSERT_TRUE(loc.knownWallMap().mainDirection());
		EXPECT_NEAR(
		    *loc.knownWallMap().mainDirection(), 0.0, mrpt::DEG2RAD(1.0));
		loc.initializeGlobal();
		int convergedAt = -1;
		for (std::size_t i = 0; i < r.sweeps.size(); i++)
		{
			const auto incr =
			    i == 0 ? mrpt::poses::CPose2D()
			           : r.sweeps[i].odometry() - r.sweeps[i - 1].odometry();
			const auto u = loc.update(incr, ex.extract(r.labeled[i]));
			const double e =
			    (u.pose.translation() - r.gt[i].translation()).norm();
			std::cerr << "global localization, seed " << seed << ", sweep " << i
			          << ": error " << e << " m, spread " << u.stdXY << " m, "
			          << u.particles << " particles, converged " << u.converged
			          << "\n";
			if (u.converged && convergedAt < 0) convergedAt = int(i);
		}
		EXPECT_GE(convergedAt, 0);
		EXPECT_LE(convergedAt, 4);
		if (convergedAt >= 0 && convergedAt <= 3) byFourthUpdate++;
		EXPECT_EQ(loc.convergedAfter(), convergedAt + 1);
		EXPECT_EQ(loc.globalUpdates(), convergedAt + 1);
		EXPECT_EQ(loc.kidnappings(), 0);
		const auto p = loc.pose();
		EXPECT_LT((p.translation() - r.gt.back().translation()).norm(), 0.15);
		EXPECT_LT(
		    std::abs(mrpt::math::wrapToPi(p.phi() - r.gt.back().phi())),
		    mrpt::DEG2RAD(2.0));
	}
	EXPECT_GE(byFourthUpdate, kSeeds / 2);
}

TEST(LocalizationAccuracy, KidnappedRobotIsDetectedAndRecovered)
{
	const SimRun& r = run("datasets/office/office.yaml", 2);
	const auto o = shippedOptions();
	Localizer loc(o.localizer);
	loc.setKnownMap(knownOffice());
	loc.initialize(r.gt[0]);
	const WallExtractor ex(o.walls);
	// Sweeps 0-2, then the robot is carried to the first later stop >= 3 m
	// away while odometry reports an ordinary step, then the rest.
	std::vector<std::size_t> order = {0, 1, 2};
	std::size_t jump = 4;
	while (jump < r.gt.size() &&
	       (r.gt[jump].translation() - r.gt[2].translation()).norm() < 3.0)
		jump++;
	ASSERT_LE(jump + 3, r.gt.size()) << "the scene's trajectory changed";
	for (std::size_t i = jump; i < r.gt.size(); i++) order.push_back(i);
	int detectedAt = -1;
	for (std::size_t k = 0; k < order.size(); k++)
	{
		const std::size_t i = order[k];
		mrpt::poses::CPose2D incr;
		if (k > 0)
			incr = i == order[k - 1] + 1
			           ? r.sweeps[i].odometry() - r.sweeps[i - 1].odometry()
			           : r.sweeps[3].odometry() - r.sweeps[2].odometry();
		const auto u = loc.update(incr, ex.extract(r.labeled[i]));
		const double e = (u.pose.translation() - r.gt[i].translation()).norm();
		std::cerr << "kidnap run, sweep " << i << ": error " << e
		          << " m, inliers " << u.inlierFraction << ", kidnapped "
		          << u.kidnapped << ", converged " << u.converged << "\n";
		if (k < 3) EXPECT_LT(e, 0.1) << "tracking before the kidnapping";
		if (u.kidnapped && detectedAt < 0) detectedAt = int(k);
	}
	EXPECT_EQ(loc.kidnappings(), 1);
	EXPECT_GE(loc.convergedAfter(), 1);
	EXPECT_GE(detectedAt, 3);
	EXPECT_LE(detectedAt, 4);
	const auto p = loc.pose();
	const auto& last = r.gt[order.back()];
	EXPECT_LT((p.translation() - last.translation()).norm(), 0.15);
	EXPECT_LT(
	    std::abs(mrpt::math::wrapToPi(p.phi() - last.phi())),
	    mrpt::DEG2RAD(2.0));
}

/** A drift run of the README's localization table and what
 * `bench_localization_table --config config/localization.ini` measured on
 * it: odometry's final heading error (deg), the shipped filter's final and
 * largest heading error (deg) and its RMSE xy (m). The same on every run
 * of one test alone, as ctest runs them (seeded simulation and filter);
 * after other tests in one process the filter draws other numbers, within
 * the margins. */
struct DriftClaim
{
	const char* scene;
	uint64_t seed;
	double odometryDeg, finalDeg, maxDeg, rmse;
};

std::ostream& operator<<(std::ostream& o, const DriftClaim& c)
{
	return o << c.scene << ":" << c.seed;
}

class DriftRun : public ::testing::TestWithParam<DriftClaim>
{
};

TEST_P(DriftRun, MainDirectionsBoundTheHeadingError)
{
	const DriftClaim& c = GetParam();
	const SimRun& r = run(c.scene, c.seed);
	const auto odo = mapRun(r, MappingLocalizer::Method::Odometry, false);
	const auto on = mapRun(r, MappingLocalizer::Method::Walls, true);
	const auto off = mapRun(r, MappingLocalizer::Method::Walls, false);
	std::cerr << c << ": odometry final yaw " << mrpt::RAD2DEG(odo.finalYaw())
	          << " deg, rmse " << odo.rmseXY() << " m; main directions on "
	          << mrpt::RAD2DEG(on.finalYaw()) << " / "
	          << mrpt::RAD2DEG(on.maxYaw()) << " deg, " << on.rmseXY()
	          << " m; off " << mrpt::RAD2DEG(off.finalYaw()) << " / "
	          << mrpt::RAD2DEG(off.maxYaw()) << " deg, " << off.rmseXY()
	          << " m\n";
	// The simulated drift itself.
	EXPECT_NEAR(mrpt::RAD2DEG(odo.finalYaw()), c.odometryDeg, 1.0);
	// Asserts <= measured + 0.1 deg final, + 0.15 deg largest, + 0.02 m
	// RMSE: every run stays <= 0.4 deg where the README says <= 0.23, so
	// a heading 10x the README's fails.
	EXPECT_LE(mrpt::RAD2DEG(on.finalYaw()), c.finalDeg + 0.1);
	EXPECT_LE(mrpt::RAD2DEG(on.maxYaw()), c.maxDeg + 0.15);
	EXPECT_LE(on.rmseXY(), c.rmse + 0.02);
	// The correction is what bounds the heading: without it the error is
	// larger (still far below odometry's).
	EXPECT_LT(on.maxYaw(), off.maxYaw());
	EXPECT_LT(off.finalYaw(), odo.finalYaw() / 3);
}

// README "Localization", the row "wall PF, main directions on (shipped)".
INSTANTIATE_TEST_SUITE_P(
    Scenes, DriftRun,
    ::testing::Values(
        DriftClaim{
            "datasets/localization/corridor.yaml", 1, 49.59, 0.00, 0.05, 0.036},
        DriftClaim{
            "datasets/localization/corridor.yaml", 3, 42.47, 0.02, 0.09, 0.029},
        DriftClaim{
            "datasets/localization/rooms.yaml", 1, 46.23, 0.05, 0.11, 0.050},
        DriftClaim{
            "datasets/localization/rooms.yaml", 3, 39.92, 0.06, 0.10, 0.048},
        DriftClaim{"datasets/office/office.yaml", 1, 50.55, 0.09, 0.24, 0.037},
        DriftClaim{
            "datasets/office/office.yaml", 3, 55.15, 0.05, 0.24, 0.058}));

TEST(LocalizationAccuracy, StockMclBaselineTracksTheRooms)
{
	const SimRun& r = run("datasets/localization/rooms.yaml", 1);
	const auto stock = mapRun(r, MappingLocalizer::Method::OccupancyMcl, false);
	const auto odo = mapRun(r, MappingLocalizer::Method::Odometry, false);
	std::cerr << "stock MCL, rooms seed 1: final yaw "
	          << mrpt::RAD2DEG(stock.finalYaw()) << " deg, rmse "
	          << stock.rmseXY() << " m\n";
	EXPECT_LT(stock.rmseXY(), odo.rmseXY() / 3);
	EXPECT_LT(stock.finalYaw(), mrpt::DEG2RAD(5));
}

namespace
{
/** Distance from a point to the outline of an axis-aligned wall box's
 * footprint (its faces), and the signed side (< 0 inside). */
double faceDistance(const BoxShape& b, double x, double y)
{
	const double dx = std::abs(x - b.center.x) - b.size.x / 2;
	const double dy = std::abs(y - b.center.y) - b.size.y / 2;
	if (dx > 0 || dy > 0)
		return std::hypot(std::max(dx, 0.0), std::max(dy, 0.0));
	return -std::min(-dx, -dy);
}
}  // namespace

TEST(LocalizationAccuracy, WallSegmentsLieOnTheSceneWalls)
{
	const SimRun& r = run("datasets/localization/rooms.yaml", 1);
	const WallExtractor ex(shippedOptions().walls);
	std::size_t segments = 0;
	double sum = 0, sumAbs = 0;
	std::size_t n = 0;
	for (std::size_t i = 0; i < r.sweeps.size(); i++)
	{
		const auto obs = ex.extract(r.labeled[i]);
		EXPECT_GE(obs.segments.size(), 2u) << "sweep " << i;
		ASSERT_TRUE(obs.dominantDirection) << "sweep " << i;
		// The walls are axis-aligned: the sweep's direction is -yaw mod 90.
		EXPECT_NEAR(
		    MainDirections::wrapQuarter(*obs.dominantDirection + r.gt[i].phi()),
		    0.0, mrpt::DEG2RAD(0.3))
		    << "sweep " << i;
		for (const auto& s : obs.segments)
		{
			segments++;
			const auto w = s.transformed(r.gt[i]);
			for (double t = 0; t <= 1.0; t += 0.25)
			{
				const auto p = w.p0 + (w.p1 - w.p0) * t;
				double best = 1e9;
				for (const auto& o : r.scene.objects)
					if (o.label == Label::Wall)
						for (const auto& prim : o.parts)
							if (const auto* b = std::get_if<BoxShape>(&prim))
							{
								const double d = faceDistance(*b, p.x, p.y);
								if (std::abs(d) < std::abs(best)) best = d;
							}
				EXPECT_LT(std::abs(best), 0.03) << "sweep " << i;
				sum += best, sumAbs += std::abs(best), n++;
			}
		}
	}
	std::cerr << segments << " segments, mean offset from the wall faces "
	          << sum / n << " m (outside > 0), mean |offset| " << sumAbs / n
	          << " m\n";
	EXPECT_LT(std::abs(sum / n), 0.01);
}
