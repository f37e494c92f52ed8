/* semnav: semantic navigation from tilting-laser sweeps */
// Semantic-map insertion time per sweep (with and without the OctoMap,
// whose cost is the baseline here), and the memory of a 50 m x 50 m map.
#include <benchmark/benchmark.h>
#include <octomap/OcTree.h>
#include <semnav/map/SemanticMap.h>

#include <filesystem>

#include "PerceivedOffice.h"

using namespace semnav;

namespace
{
const test::PerceivedRun& office()
{
	static const test::PerceivedRun o =
	    test::perceivedOffice("semnav_bench_map");
	return o;
}

void insertAll(benchmark::State& state, bool withOctomap)
{
	const test::PerceivedRun& o = office();
	SemanticMap::TOptions opts;
	opts.octomap = withOctomap;
	for (auto _ : state)
	{
		SemanticMap m(opts);
		for (std::size_t i = 0; i < o.sweeps.size(); i++)
			m.insert(o.sweeps[i], o.labeled[i], o.truePoses[i]);
		benchmark::DoNotOptimize(m.get("cost").data());
	}
	state.counters["sweeps_per_s"] = benchmark::Counter(
	    static_cast<double>(o.sweeps.size()),
	    benchmark::Counter::kIsIterationInvariantRate);
}

void BM_MapInsertOfficeSweeps(benchmark::State& s)
{
	insertAll(s, true);
}
void BM_MapInsertOfficeSweepsNoOctomap(benchmark::State& s)
{
	insertAll(s, false);
}

void BM_MapMemory50x50m(benchmark::State& state)
{
	for (auto _ : state)
	{
		SemanticMap::TOptions opts;
		opts.growMargin = 0;
		SemanticMap m(opts);
		m.growToInclude(0, 0, 50, 50);
		std::size_t bytes =
		    m.occupancyGrid().getRawMap().size() * sizeof(int8_t);
		for (const auto& name : m.layers())
			bytes += m.get(name).size() * sizeof(float);
		state.counters["cells"] = static_cast<double>(m.geometry().cellCount());
		state.counters["MiB"] = static_cast<double>(bytes) / (1024.0 * 1024.0);
	}
}
}  // namespace

BENCHMARK(BM_MapInsertOfficeSweeps)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MapInsertOfficeSweepsNoOctomap)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MapMemory50x50m)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_MAIN();
