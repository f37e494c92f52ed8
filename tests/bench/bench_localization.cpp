/* semnav: semantic navigation from tilting-laser sweeps */
// Particle-filter update time per 1000 particles (target <= 1 ms): the wall
// filter (WallMonteCarlo2D: prediction, wall likelihood, main-direction
// correction, resampling) against MRPT's stock CMonteCarloLocalization2D
// with the occupancy likelihood field on the horizontal scan line, same
// particle count, same map (office, true poses), in the same run. Prints
// the medians and their ratio at the end.
#include <benchmark/benchmark.h>
#include <semnav/localization/Localizer.h>
#include <semnav/localization/OccupancyMcl.h>
#include <semnav/localization/WallExtractor.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/perception/PerceptionPipeline.h>
#include <semnav/scan/GroundTruthLog.h>
#include <semnav/scan/RawlogSweepReader.h>
#include <semnav/sim/SceneLoader.h>
#include <semnav/sim/SimulationRunner.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>

using namespace semnav;

namespace
{
struct Office
{
	std::vector<Sweep> sweeps;
	std::vector<LabeledSweep> labeled;
	std::vector<mrpt::poses::CPose2D> gt;
	std::unique_ptr<SemanticMap> map;
};

const Office& office()
{
	static const Office o = []
	{
		Office out;
		const Scene scene = SceneLoader::loadFile(
		    std::string(SEMNAV_SOURCE_DIR) + "/datasets/office/office.yaml");
		const auto dir =
		    std::filesystem::temp_directory_path() / "semnav_bench_loc";
		const auto res =
		    SimulationRunner(scene, SimulationRunner::TOptions(), 1)
		        .run(dir.string());
		const GroundTruthLog gt(dir.string(), scene.name);
		PerceptionPipeline p;
		out.sweeps = readRawlogSweeps(res.rawlogPath);
		out.map = std::make_unique<SemanticMap>();
		for (const auto& s : out.sweeps)
		{
			out.labeled.push_back(p.process(s));
			out.gt.push_back(gt.pose(s.index()));
			out.map->insert(s, out.labeled.back(), out.gt.back());
		}
		return out;
	}();
	return o;
}

std::map<std::string, std::vector<double>>& samples()
{
	static std::map<std::string, std::vector<double>> s;
	return s;
}

Localizer::TOptions fixedOptions(int particles)
{
	Localizer::TOptions o;
	o.adaptiveSampleSize = false;
	o.particles = particles;
	return o;
}

const std::size_t kSweep = 4;
const mrpt::poses::CPose2D kStep(0.05, 0, 0.005);

void BM_WallFilterUpdate(benchmark::State& state)
{
	const Office& o = office();
	const int n = static_cast<int>(state.range(0));
	Localizer loc(fixedOptions(n));
	loc.setKnownMap(*o.map);
	const auto obs = WallExtractor().extract(o.labeled[kSweep]);
	loc.initialize(o.gt[kSweep]);
	auto& v = samples()["walls/" + std::to_string(n)];
	for (auto _ : state)
	{
		const auto u = loc.update(kStep, obs);
		v.push_back(u.ms);
		benchmark::DoNotOptimize(u);
	}
	state.counters["particles"] = n;
	state.counters["wall_samples"] = double(obs.samples.size());
}

void BM_StockMclUpdate(benchmark::State& state)
{
	const Office& o = office();
	const int n = static_cast<int>(state.range(0));
	OccupancyMcl mcl(fixedOptions(n));
	mcl.setMap(OccupancyMcl::mrptGrid(*o.map));
	const auto scan = OccupancyMcl::horizontalScan(o.sweeps[kSweep]);
	mcl.initialize(o.gt[kSweep]);
	auto& v = samples()["stock/" + std::to_string(n)];
	for (auto _ : state)
	{
		const auto u = mcl.update(kStep, scan);
		v.push_back(u.ms);
		benchmark::DoNotOptimize(u);
	}
	state.counters["particles"] = n;
}

void BM_WallLikelihoodOnly(benchmark::State& state)
{
	const Office& o = office();
	const int n = static_cast<int>(state.range(0));
	WallMap map;
	map.buildFromSemanticMap(*o.map);
	const auto obs = WallExtractor().extract(o.labeled[kSweep]);
	const auto& g = o.gt[kSweep];
	for (auto _ : state)
	{
		double s = 0;
		for (int i = 0; i < n; i++)
			s += map.logLikelihood(
			    g.x() + 1e-4 * i, g.y(), g.phi(), obs.samples);
		benchmark::DoNotOptimize(s);
	}
	state.counters["particles"] = n;
}
}  // namespace

BENCHMARK(BM_WallFilterUpdate)
    ->Arg(1000)
    ->Arg(10000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_StockMclUpdate)
    ->Arg(1000)
    ->Arg(10000)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_WallLikelihoodOnly)->Arg(1000)->Unit(benchmark::kMicrosecond);

int main(int argc, char** argv)
{
	benchmark::Initialize(&argc, argv);
	if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
	benchmark::RunSpecifiedBenchmarks();
	benchmark::Shutdown();
	auto median = [](std::vector<double> v)
	{
		if (v.empty()) return 0.0;
		std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
		return v[v.size() / 2];
	};
	for (const char* n : {"1000", "10000"})
	{
		const double w = median(samples()[std::string("walls/") + n]);
		const double s = median(samples()[std::string("stock/") + n]);
		if (w <= 0 || s <= 0) continue;
		std::printf(
		    "%s particles (wall clock): walls %.3f ms (%.3f ms per 1000), "
		    "stock MCL %.3f "
		    "ms (%.3f ms per 1000), stock / walls = %.1f\n",
		    n, w, w * 1000 / std::stod(n), s, s * 1000 / std::stod(n), s / w);
	}
	return 0;
}
