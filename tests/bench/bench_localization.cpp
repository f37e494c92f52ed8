/* semnav: semantic navigation from tilting-laser sweeps */
// Particle-filter update time per 1000 particles (target <= 1 ms): the wall
// filter (WallMonteCarlo2D: prediction, wall likelihood, main-direction
// correction, resampling) against MRPT's stock CMonteCarloLocalization2D
// with the occupancy likelihood field on the horizontal scan line, same
// particle count, same map (office, true poses), in the same run; and the
// wall filter with the semantic evidence (SemanticEvidenceMap: labelled
// points and objects against the map's) against walls only. Prints the
// medians and their ratios at the end.
#include <benchmark/benchmark.h>
#include <semnav/localization/Localizer.h>
#include <semnav/localization/OccupancyMcl.h>
#include <semnav/localization/SemanticEvidenceMap.h>
#include <semnav/localization/SemanticExtractor.h>
#include <semnav/localization/WallExtractor.h>
#include <semnav/map/SemanticMap.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>

#include "PerceivedOffice.h"

using namespace semnav;

namespace
{
/** The perceived office and its map built with the true poses. */
struct Office : test::PerceivedRun
{
	std::unique_ptr<SemanticMap> map;
};

const Office& office()
{
	static const Office o = []
	{
		Office out;
		static_cast<test::PerceivedRun&>(out) =
		    test::perceivedOffice("semnav_bench_loc");
		out.map = std::make_unique<SemanticMap>();
		for (std::size_t i = 0; i < out.sweeps.size(); i++)
			out.map->insert(out.sweeps[i], out.labeled[i], out.truePoses[i]);
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
	loc.initialize(o.truePoses[kSweep]);
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

void BM_SemanticFilterUpdate(benchmark::State& state)
{
	const Office& o = office();
	const int n = static_cast<int>(state.range(0));
	Localizer loc(fixedOptions(n));
	loc.setKnownMap(*o.map);
	SemanticEvidenceMap semantic;
	semantic.build(*o.map);
	loc.setSemanticMap(&semantic);
	const auto obs = WallExtractor().extract(o.labeled[kSweep]);
	const auto sem = SemanticExtractor().extract(o.labeled[kSweep]);
	loc.initialize(o.truePoses[kSweep]);
	auto& v = samples()["semantic/" + std::to_string(n)];
	for (auto _ : state)
	{
		const auto u = loc.update(kStep, obs, &sem);
		v.push_back(u.ms);
		benchmark::DoNotOptimize(u);
	}
	state.counters["particles"] = n;
	state.counters["semantic_points"] =
	    double(sem.classSamples.size() + sem.groundSamples.size());
}

void BM_StockMclUpdate(benchmark::State& state)
{
	const Office& o = office();
	const int n = static_cast<int>(state.range(0));
	OccupancyMcl mcl(fixedOptions(n));
	mcl.setMap(OccupancyMcl::mrptGrid(*o.map));
	const auto scan = OccupancyMcl::horizontalScan(o.sweeps[kSweep]);
	mcl.initialize(o.truePoses[kSweep]);
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
	const auto& g = o.truePoses[kSweep];
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
BENCHMARK(BM_SemanticFilterUpdate)
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
		const double m = median(samples()[std::string("semantic/") + n]);
		if (m > 0)
			std::printf(
			    "%s particles: walls + semantic evidence %.3f ms (%.3f ms per "
			    "1000), (walls + semantic) / walls = %.2f\n",
			    n, m, m * 1000 / std::stod(n), m / w);
	}
	return 0;
}
