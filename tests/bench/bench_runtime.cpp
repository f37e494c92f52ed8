/* semnav: semantic navigation from tilting-laser sweeps */
// The robot loop's cost per sweep (what semnav-robot does with each sweep it
// takes) against the sweep's own duration, early and late in a long run on a
// generated building (a 48 m corridor with 12 rooms, wastebaskets in every
// other room), stop-and-scan every 0.5 m along the corridor, back and forth:
// - perception (rules, cascades, 3D checks: SweepPerception),
// - particle filter + insertion into the map (MappingLocalizer::process,
//   the same update and insertion semnav-robot runs),
// - the localizer's refresh on the grown map (Localizer::updateKnownMap
//   and SemanticEvidenceMap::update, what StopAndScanLocalizer::mapChanged()
//   does: around the cells the insertion changed),
// - a replan to the nearest wastebasket (one SemanticPlanner for the run,
//   repaired after each insertion, as the navigator's).
// BM_RobotLoop/N runs N sweeps once and reports, as counters, the median
// loop time of the first 10 and of the last 10 sweeps, their share of the
// sweep's duration (lines x 1/37.5 s) and each part's median.
// Run with
//   bench_runtime --benchmark_filter='BM_RobotLoop/500'
#include <benchmark/benchmark.h>
#include <mrpt/config/CConfigFile.h>
#include <semnav/common/ConfigChecks.h>
#include <semnav/common/Percentile.h>
#include <semnav/common/Timing.h>
#include <semnav/detection/SweepPerception.h>
#include <semnav/localization/Localizer.h>
#include <semnav/localization/MappingLocalizer.h>
#include <semnav/localization/SemanticEvidenceMap.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/nav/NavigationConfig.h>
#include <semnav/planning/SemanticPlanner.h>
#include <semnav/scan/RawlogSweepReader.h>
#include <semnav/sim/SceneLoader.h>
#include <semnav/sim/SimulationRunner.h>

#include <chrono>
#include <filesystem>
#include <sstream>

using namespace semnav;

namespace
{
const std::string kSrc = SEMNAV_SOURCE_DIR;

/** A corridor along x (y 0..2.4) with rooms on its north side, each with a
 * 1 m door gap; a wastebasket in every other room. The trajectory: `stops`
 * stops 0.5 m apart along the corridor, turning back at its ends. */
std::string building(int stops)
{
	const double length = 48, roomW = 4.0, roomD = 4.0;
	std::ostringstream y;
	y << "name: building\nbounds: [0, 0, " << length << ", " << 2.4 + roomD
	  << "]\nceiling_height: 2.7\nobjects:\n";
	const auto wall = [&](double cx, double cy, double sx, double sy)
	{
		y << "  - {label: wall, box: {center: [" << cx << ", " << cy
		  << ", 1.35], size: [" << sx << ", " << sy << ", 2.7]}}\n";
	};
	wall(length / 2, 0.05, length, 0.1);              // corridor south
	wall(0.05, (2.4 + roomD) / 2, 0.1, 2.4 + roomD);  // west end
	wall(length - 0.05, (2.4 + roomD) / 2, 0.1, 2.4 + roomD);
	wall(length / 2, 2.4 + roomD - 0.05, length, 0.1);  // rooms north
	for (int r = 0; r * roomW < length; r++)
	{
		const double x0 = r * roomW;
		// The corridor's north wall with a door gap x0 + 1.5 .. x0 + 2.5.
		wall(x0 + 0.75, 2.4, 1.5, 0.1);
		wall(x0 + 3.25, 2.4, 1.5, 0.1);
		if (r > 0) wall(x0, 2.4 + roomD / 2, 0.1, roomD);  // between rooms
		if (r % 2 == 0)
			y << "  - {label: wastebasket, cylinder: {center: [" << x0 + 0.5
			  << ", " << 2.4 + roomD - 0.5
			  << ", 0.2], radius: 0.15, height: 0.4}}\n";
	}
	y << "odometry: {trans_noise: 0.02, rot_noise_deg_per_m: 2.0, "
	     "rot_bias_deg_per_m: 1.0}\ntrajectory:\n";
	double x = 1.0, dir = 1;
	for (int i = 0; i < stops; i++)
	{
		y << "  - [" << x << ", 1.2, " << (dir > 0 ? 0 : 180) << "]\n";
		if (x + dir * 0.5 > length - 1.0 || x + dir * 0.5 < 1.0) dir = -dir;
		x += dir * 0.5;
	}
	return y.str();
}

struct Parts
{
	std::vector<double> loop, perception, localizeInsert, refresh, replan;
};

void BM_RobotLoop(benchmark::State& state)
{
	const int n = static_cast<int>(state.range(0));
	const Scene scene = SceneLoader::parse(building(n), "building.yaml");
	const auto dir =
	    std::filesystem::temp_directory_path() / "semnav_bench_runtime";
	const auto sim = SimulationRunner(scene, SimulationRunner::TOptions(), 1)
	                     .run(dir.string());
	const std::vector<Sweep> sweeps = readRawlogSweeps(sim.rawlogPath);
	const NavigationConfig nav = NavigationConfig::load(
	    kSrc + "/config/navigation.ini", kSrc + "/config/planning.ini");
	MappingLocalizer::TOptions loc;
	loc.loadFromConfigFile(
	    *openIniFile(
	        kSrc + "/config/localization.ini",
	        MappingLocalizer::TOptions::sections()),
	    "");
	const auto cascades =
	    CascadeDetector::TOptions::fromIniFile(kSrc + "/config/cascade.ini");
	const double sweepSeconds =
	    static_cast<double>(sweeps.front().rows()) / 37.5;

	for (auto _ : state)
	{
		SweepPerception perception(PerceptionPipeline::TOptions(), cascades);
		MappingLocalizer localizer(loc);
		localizer.setMinLoggingLevel(mrpt::system::LVL_ERROR);
		SemanticMap map(nav.map);
		Localizer known(loc.localizer);
		SemanticEvidenceMap evidence(loc.semantic);
		// One planner for the run, as the navigator holds one: it repairs
		// its field after each insertion.
		SemanticPlanner planner(map, nav.cnn, nav.traversability);
		Parts p;
		for (const Sweep& sweep : sweeps)
		{
			auto t = std::chrono::steady_clock::now();
			const auto t0 = t;
			LabeledSweep labeled;
			perception.process(sweep, labeled);
			p.perception.push_back(msSince(t));
			t = std::chrono::steady_clock::now();
			const auto pose = localizer.process(sweep, labeled, map);
			p.localizeInsert.push_back(msSince(t));
			t = std::chrono::steady_clock::now();
			known.updateKnownMap(map);
			evidence.update(map);
			p.refresh.push_back(msSince(t));
			t = std::chrono::steady_clock::now();
			try
			{
				planner.toLabelShared(
				    pose.x(), pose.y(), Label::Wastebasket,
				    nav.navigationProfile());
			}
			catch (const PlanningError&)
			{
				// No wastebasket in the map yet, or none reachable: the
				// planning work was done all the same.
			}
			p.replan.push_back(msSince(t));
			p.loop.push_back(msSince(t0));
		}
		const auto first = [](const std::vector<double>& v)
		{ return median(std::vector<double>(v.begin(), v.begin() + 10)); };
		const auto last = [](const std::vector<double>& v)
		{ return median(std::vector<double>(v.end() - 10, v.end())); };
		state.counters["sweep_s"] = sweepSeconds;
		state.counters["first10_loop_ms"] = first(p.loop);
		state.counters["last10_loop_ms"] = last(p.loop);
		state.counters["first10_share_pct"] =
		    100 * first(p.loop) / 1000 / sweepSeconds;
		state.counters["last10_share_pct"] =
		    100 * last(p.loop) / 1000 / sweepSeconds;
		state.counters["last10_perception_ms"] = last(p.perception);
		state.counters["last10_pf_insert_ms"] = last(p.localizeInsert);
		state.counters["last10_refresh_ms"] = last(p.refresh);
		state.counters["last10_replan_ms"] = last(p.replan);
		state.counters["first10_perception_ms"] = first(p.perception);
		state.counters["first10_pf_insert_ms"] = first(p.localizeInsert);
		state.counters["first10_refresh_ms"] = first(p.refresh);
		state.counters["first10_replan_ms"] = first(p.replan);
		state.counters["map_cells"] =
		    static_cast<double>(map.geometry().cellCount());
	}
}
}  // namespace

BENCHMARK(BM_RobotLoop)
    ->Arg(20)
    ->Arg(500)
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

BENCHMARK_MAIN();
