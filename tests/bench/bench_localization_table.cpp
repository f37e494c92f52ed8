/* semnav: semantic navigation from tilting-laser sweeps */
// Mapping with localization on simulated drift runs: the particle filter as
// configured (walls, semantic evidence, prediction guard), with the
// semantic evidence and / or the guard off, with main directions off,
// odometry alone and MRPT's stock CMonteCarloLocalization2D (likelihood
// field, horizontal scan line), one table. Usage:
//   bench_localization_table [--config C.ini] [--out DIR] [--short]
//                            SCENE:SEED ...
// (default: datasets/localization/*.yaml and the office, seeds 1 and 3;
// --short: without the main-directions-off and stock MCL rows).
#include <mrpt/config/CConfigFile.h>
#include <semnav/common/ConfigChecks.h>
#include <semnav/localization/MappingLocalizer.h>
#include <semnav/localization/TrajectoryError.h>
#include <semnav/localization/WallExtractor.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/perception/PerceptionPipeline.h>
#include <semnav/scan/GroundTruthLog.h>
#include <semnav/scan/RawlogSweepReader.h>
#include <semnav/sim/SceneLoader.h>
#include <semnav/sim/SimulationRunner.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

using namespace semnav;
namespace fs = std::filesystem;

namespace
{
struct Mode
{
	const char* name;
	MappingLocalizer::Method method;
	std::function<void(MappingLocalizer::TOptions&)> change;
	bool inShort;
};

void noSemantic(MappingLocalizer::TOptions& o)
{
	o.semantic.classPoints = o.semantic.groundPoints = o.semantic.objectPoints =
	    0;
}

double median(std::vector<double> v)
{
	if (v.empty()) return 0;
	std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
	return v[v.size() / 2];
}
}  // namespace

/** One row of the table: mapping with localization by mode `m`. */
void tableRow(
    const Mode& m, const MappingLocalizer::TOptions& opts,
    const std::vector<Sweep>& sweeps, const std::vector<LabeledSweep>& labeled,
    const GroundTruthLog& gt, const std::string& runName, bool verbose)
{
	MappingLocalizer::TOptions o = opts;
	m.change(o);
	MappingLocalizer loc(o, m.method);
	SemanticMap map;
	TrajectoryError err;
	std::vector<double> ms, parts;
	double maxStd = 0;
	int guarded = 0;
	for (std::size_t i = 0; i < sweeps.size(); i++)
	{
		// Verbose: the wall map before this sweep, scored at the true
		// pose and at the estimate.
		std::string diag;
		const auto& wm = loc.wallMap();
		WallObservation ob;
		if (verbose) ob = WallExtractor(o.walls).extract(labeled[i]);
		const auto& og = gt.pose(sweeps[i].index());
		const double llGt =
		    wm.empty() ? 0
		               : wm.logLikelihood(og.x(), og.y(), og.phi(), ob.samples);
		const auto md = wm.mainDirection();
		const auto pose = loc.process(sweeps[i], labeled[i], map);
		if (verbose)
		{
			char buf[256];
			std::snprintf(
			    buf, sizeof(buf),
			    "    map dir %.2f, sweep dir %.2f, ll at truth %.1f, "
			    "at "
			    "estimate %.1f\n",
			    md ? mrpt::RAD2DEG(*md) : 99.0,
			    ob.dominantDirection ? mrpt::RAD2DEG(*ob.dominantDirection)
			                         : 99.0,
			    llGt,
			    wm.empty() ? 0.0
			               : wm.logLikelihood(
			                     pose.x(), pose.y(), pose.phi(), ob.samples));
			diag = buf;
		}
		const auto& g = gt.pose(sweeps[i].index());
		err.add(pose, g);
		if (verbose)
		{
			const auto& u = loc.lastUpdate();
			std::fprintf(
			    stderr,
			    "  %s sweep %zu: est (%.3f %.3f %.2f) gt (%.3f %.3f "
			    "%.2f) std %.3f m %.2f deg, %zu particles, ess %.2f, "
			    "%zu walls, corrected %d; largest std %.3f m at %.0f "
			    "deg, guarded %d (variance ratio %.2f), semantic %zu + "
			    "%zu + %zu (map rebuilt in %.1f ms)\n",
			    m.name, i, pose.x(), pose.y(), mrpt::RAD2DEG(pose.phi()), g.x(),
			    g.y(), mrpt::RAD2DEG(g.phi()), u.stdXY, mrpt::RAD2DEG(u.stdYaw),
			    u.particles, u.ess, loc.lastObservation().segments.size(),
			    int(u.headingCorrected), u.largestStd,
			    mrpt::RAD2DEG(u.largestStdDirection), u.unconstrained,
			    u.varianceRatio, loc.lastSemantic().classSamples.size(),
			    loc.lastSemantic().groundSamples.size(),
			    loc.lastSemantic().objects.size(), loc.semanticBuildMs());
			std::fputs(diag.c_str(), stderr);
		}
		if (i > 0)
		{
			const auto& u = loc.lastUpdate();
			ms.push_back(u.ms);
			parts.push_back(u.particles);
			maxStd = std::max(maxStd, u.largestStd);
			guarded += u.unconstrained > 0;
		}
	}
	char timing[128] = "- | - | - | -";
	if (m.method != MappingLocalizer::Method::Odometry)
		std::snprintf(
		    timing, sizeof(timing), "%.3f / %.3f | %d / %zu | %.2f | %.0f",
		    loc.lastUpdate().largestStd, maxStd, guarded, sweeps.size() - 1,
		    median(ms), median(parts));
	std::printf(
	    "| %s | %s | %.2f | %.2f | %.3f | %s |\n", runName.c_str(), m.name,
	    mrpt::RAD2DEG(err.finalYaw()), mrpt::RAD2DEG(err.maxYaw()),
	    err.rmseXY(), timing);
	std::fflush(stdout);
}

int main(int argc, char** argv)
{
	std::string config,
	    outDir = (fs::temp_directory_path() / "semnav_loc_table").string();
	std::vector<std::string> runs;
	bool verbose = false, shortTable = false;
	for (int i = 1; i < argc; i++)
	{
		const std::string a = argv[i];
		if (a == "--verbose")
			verbose = true;
		else if (a == "--short")
			shortTable = true;
		else if (a == "--config" && i + 1 < argc)
			config = argv[++i];
		else if (a == "--out" && i + 1 < argc)
			outDir = argv[++i];
		else
			runs.push_back(a);
	}
	const std::string src = SEMNAV_SOURCE_DIR;
	if (runs.empty())
	{
		std::vector<std::string> scenes;
		for (const auto& e :
		     fs::directory_iterator(src + "/datasets/localization"))
			if (e.path().extension() == ".yaml") scenes.push_back(e.path());
		std::sort(scenes.begin(), scenes.end());
		scenes.push_back(src + "/datasets/office/office.yaml");
		for (const auto& s : scenes)
			for (int seed : {1, 3})
				runs.push_back(s + ":" + std::to_string(seed));
	}
	MappingLocalizer::TOptions opts;
	if (!config.empty())
		opts.loadFromConfigFile(
		    *openIniFile(config, MappingLocalizer::TOptions::sections()), "");
	using Opt = MappingLocalizer::TOptions;
	const auto walls = MappingLocalizer::Method::Walls;
	const Mode modes[] = {
	    {"PF as configured", walls, [](Opt&) {}, true},
	    {"PF, no guard", walls, [](Opt& o) { o.guard.enabled = false; }, true},
	    {"PF walls only", walls, noSemantic, true},
	    {"PF walls only, no guard (before)", walls,
	     [](Opt& o)
	     {
		     noSemantic(o);
		     o.guard.enabled = false;
	     },
	     true},
	    {"PF, main directions off", walls,
	     [](Opt& o) { o.localizer.mainDirections = false; }, false},
	    {"odometry only", MappingLocalizer::Method::Odometry, [](Opt&) {},
	     true},
	    {"MRPT stock MCL (likelihood field, horizontal line)",
	     MappingLocalizer::Method::OccupancyMcl, [](Opt&) {}, false}};

	std::printf(
	    "| run | method | final yaw err (deg) | max yaw err (deg) | RMSE xy "
	    "(m) | largest std (m, final / max) | guarded updates "
	    "| ms / update (median) | particles (median) "
	    "|\n|---|---|---|---|---|---|---|---|---|\n");
	for (const auto& run : runs)
	{
		const auto colon = run.rfind(':');
		const std::string scenePath = run.substr(0, colon);
		const uint64_t seed = std::stoull(run.substr(colon + 1));
		const Scene scene = SceneLoader::loadFile(scenePath);
		const std::string dir =
		    outDir + "/" + scene.name + "-s" + std::to_string(seed);
		const auto res =
		    SimulationRunner(scene, SimulationRunner::TOptions(), seed)
		        .run(dir);
		const GroundTruthLog gt(dir, scene.name);
		const auto sweeps = readRawlogSweeps(res.rawlogPath);
		PerceptionPipeline perception;
		std::vector<LabeledSweep> labeled;
		for (const auto& s : sweeps) labeled.push_back(perception.process(s));
		const std::string runName = scene.name + " s" + std::to_string(seed);
		for (const auto& m : modes)
		{
			if (shortTable && !m.inShort) continue;
			tableRow(m, opts, sweeps, labeled, gt, runName, verbose);
		}
	}
	return 0;
}
