/* semnav: semantic navigation from tilting-laser sweeps */
// One full 211 x 361 sweep of a 30-object scene: accelerated vs brute-force
// ray casting, single thread vs all threads; plus an outdoor sweep where
// terrain marching dominates. Run with
//   bench_sim --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <semnav/sim/RayCaster.h>
#include <semnav/sim/SimulationRunner.h>
#include <semnav/sim/TiltingLaserSimulator.h>

#include <cmath>
#include <random>

#include "../sim/ClutteredScene.h"

using namespace semnav;

namespace
{
using test::clutteredScene;
using test::sceneObject;

/** Outdoor: 30 x 30 m of rough grass and sidewalk (terrain marching
 * dominates), a few obstacles. */
Scene outdoorScene()
{
	Scene s;
	s.name = "outdoor";
	s.bounds = {0, 0, 30, 30};
	int id = 0;
	auto add = [&](Label l, ScenePrimitive p)
	{ s.objects.push_back(sceneObject(l, ++id, std::move(p))); };
	add(Label::Grass, TerrainShape{{{0, 0}, {30, 0}, {30, 14}, {0, 14}}, 0.03});
	add(Label::Grass,
	    TerrainShape{{{0, 16}, {30, 16}, {30, 30}, {0, 30}}, 0.03});
	add(Label::Sidewalk,
	    TerrainShape{{{0, 14}, {30, 14}, {30, 16}, {0, 16}}, 0.005});
	std::mt19937_64 rng(8);
	std::uniform_real_distribution<double> u(0, 1);
	for (int k = 0; k < 10; k++)
		add(Label::Obstacle, BoxShape{
		                         {30 * u(rng), 30 * u(rng), 0.5},
		                         {0.5, 0.5, 1.0},
		                         2 * M_PI * u(rng)});
	return s;
}

void runSweep(
    benchmark::State& state, RayCaster::Mode mode, int threads,
    bool outdoor = false)
{
	const Scene scene = outdoor ? outdoorScene() : clutteredScene();
	RayCaster rc(scene, 1);
	rc.setMode(mode);
	TiltingLaserSimulator sim(rc, SensorSpec{}, 1);
	sim.setThreads(threads);
	std::size_t k = 0;
	for (auto _ : state)
	{
		const mrpt::math::TPose2D pose = outdoor
		                                     ? mrpt::math::TPose2D(15, 12, 0.4)
		                                     : mrpt::math::TPose2D(6, 4, 0.4);
		auto sw = sim.simulate(pose, k++, SimulationRunner::epoch(), 1 / 37.5);
		benchmark::DoNotOptimize(sw.labels.data);
	}
	state.counters["rays/s"] = benchmark::Counter(
	    double(state.iterations()) * sim.lineCount() * sim.beamCount(),
	    benchmark::Counter::kIsRate);
}

void BM_SweepAccelerated1Thread(benchmark::State& s)
{
	runSweep(s, RayCaster::Mode::Accelerated, 1);
}
void BM_SweepBruteForce1Thread(benchmark::State& s)
{
	runSweep(s, RayCaster::Mode::BruteForce, 1);
}
void BM_SweepAcceleratedAllThreads(benchmark::State& s)
{
	runSweep(s, RayCaster::Mode::Accelerated, 0);
}
void BM_SweepBruteForceAllThreads(benchmark::State& s)
{
	runSweep(s, RayCaster::Mode::BruteForce, 0);
}
void BM_OutdoorSweepAccelerated1Thread(benchmark::State& s)
{
	runSweep(s, RayCaster::Mode::Accelerated, 1, true);
}
void BM_OutdoorSweepBruteForce1Thread(benchmark::State& s)
{
	runSweep(s, RayCaster::Mode::BruteForce, 1, true);
}
}  // namespace

BENCHMARK(BM_SweepAccelerated1Thread)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_SweepBruteForce1Thread)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_SweepAcceleratedAllThreads)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_SweepBruteForceAllThreads)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_OutdoorSweepAccelerated1Thread)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_OutdoorSweepBruteForce1Thread)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

BENCHMARK_MAIN();
