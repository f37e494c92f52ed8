/* semnav: semantic navigation from tilting-laser sweeps */
// One navigation step of semnav-nav on the office (ground-truth map from
// datasets/office/office.yaml, 5 cm, safe profile, robot in the hall half
// way to the nearest wastebasket):
// - BM_Replan: SemanticNavigator::replan() = traversability u + CNN field +
//   path + line-of-sight thinning + navigateWaypoints();
// - BM_NavigatorStep: SemanticNavigator::step() = MRPT's reactive
//   navigationStep() (ray-cast scan of 2 x 240 beams, TP-space transform of
//   3 PTGs, holonomic method, motion decision) + the path-blocked check;
// - BM_ReplanAndStep: both, the worst-case step (a step that replans);
// - BM_SenseObstacles, BM_CollisionCheck: the simulator's share;
// - BM_PlanCnn (CNN field to the fixed point + path) against, in the same
//   run, the binary-heap Dijkstra oracle on the same u and goal regions of
//   every washbasin: full cost field (BM_PlanDijkstra, what the CNN
//   computes) and stopped at the start (BM_PlanDijkstraEarlyStop);
//   BM_Traversability: u (C-space, profile influence), built by every
//   replan before either.
// Run with
//   bench_nav --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/nav/RobotNavInterface.h>
#include <semnav/nav/SemanticNavigator.h>
#include <semnav/navsim/SceneMapBuilder.h>
#include <semnav/navsim/SimulationConfig.h>
#include <semnav/planning/CnnPlanner.h>
#include <semnav/planning/DijkstraPlanner.h>
#include <semnav/planning/SemanticPlanner.h>
#include <semnav/sim/SceneLoader.h>
#include <semnav/sim/SimulatedRobot.h>

#include <memory>

using namespace semnav;

namespace
{
struct Fixture
{
	SimulationConfig config;
	Scene scene;
	SemanticMap map;
	std::unique_ptr<SimulatedRobot> robot;
	std::unique_ptr<RobotNavInterface> robotInterface;
	std::unique_ptr<SemanticNavigator> nav;

	Fixture()
	    : config(SimulationConfig::load(
	          std::string(SEMNAV_SOURCE_DIR) + "/config/navigation.ini",
	          std::string(SEMNAV_SOURCE_DIR) + "/config/planning.ini",
	          std::string(SEMNAV_SOURCE_DIR) + "/config/sim.ini")),
	      scene(SceneLoader::loadFile(
	          std::string(SEMNAV_SOURCE_DIR) + "/datasets/office/office.yaml")),
	      map(config.map)
	{
		SceneMapBuilder::build(scene, map);
		robot = std::make_unique<SimulatedRobot>(
		    scene, config.robot, mrpt::math::TPose2D(5.0, 1.5, 0.8));
		robotInterface = std::make_unique<RobotNavInterface>(
		    robot->base(), robot->truePose(), robot->obstacles(), *robot,
		    config.robotInterface);
		robotInterface->setMinLoggingLevel(mrpt::system::LVL_ERROR);
		nav = std::make_unique<SemanticNavigator>(
		    *robotInterface, map, *config.mrptSections, config.cnn,
		    config.traversability, config.navigator);
		nav->setMinLoggingLevel(mrpt::system::LVL_ERROR);
		robot->base().setMinLoggingLevel(mrpt::system::LVL_ERROR);
		nav->start(NavCommand::nearest(Label::Washbasin));
		// A few steps so the navigator is under way.
		for (int i = 0; i < 20; i++)
		{
			nav->step();
			robot->tick();
		}
	}
};

Fixture& fixture()
{
	static Fixture f;
	return f;
}

void BM_Replan(benchmark::State& st)
{
	auto& f = fixture();
	for (auto _ : st)
		benchmark::DoNotOptimize(
		    f.nav->replan(SemanticNavigator::ReplanReason::MapChanged));
	st.counters["cells"] = static_cast<double>(f.map.geometry().cellCount());
}
BENCHMARK(BM_Replan)->Unit(benchmark::kMillisecond);

void BM_NavigatorStep(benchmark::State& st)
{
	auto& f = fixture();
	f.nav->replan(SemanticNavigator::ReplanReason::MapChanged);
	for (auto _ : st)
	{
		f.nav->step();
		st.PauseTiming();
		// Keep the scene still: the same situation every iteration.
		f.robotInterface->stop(false);
		st.ResumeTiming();
	}
}
BENCHMARK(BM_NavigatorStep)->Unit(benchmark::kMillisecond);

void BM_ReplanAndStep(benchmark::State& st)
{
	auto& f = fixture();
	for (auto _ : st)
	{
		f.nav->replan(SemanticNavigator::ReplanReason::MapChanged);
		f.nav->step();
	}
}
BENCHMARK(BM_ReplanAndStep)->Unit(benchmark::kMillisecond);

void BM_SenseObstacles(benchmark::State& st)
{
	auto& f = fixture();
	mrpt::maps::CSimplePointsMap obs;
	mrpt::system::TTimeStamp t;
	for (auto _ : st) f.robotInterface->senseObstacles(obs, t);
	st.counters["points"] = static_cast<double>(obs.size());
}
BENCHMARK(BM_SenseObstacles)->Unit(benchmark::kMillisecond);

void BM_CollisionCheck(benchmark::State& st)
{
	auto& f = fixture();
	for (auto _ : st)
		benchmark::DoNotOptimize(
		    f.robot->base().inCollision(f.robot->base().pose()));
}
BENCHMARK(BM_CollisionCheck)->Unit(benchmark::kMillisecond);
/** The inputs of one replan's plan: u and the goal regions of every
 * washbasin, from the robot's pose. */
const SemanticPlanner::Plan& washbasinPlan()
{
	static const SemanticPlanner::Plan p = []
	{
		auto& f = fixture();
		const SemanticPlanner planner(
		    f.map, f.config.cnn, f.config.traversability);
		const auto r = f.robot->base().pose();
		return planner.toLabel(r.x, r.y, Label::Washbasin, f.nav->profile());
	}();
	return p;
}

void BM_PlanCnn(benchmark::State& st)
{
	const auto& p = washbasinPlan();
	const CnnPlanner cnn(fixture().config.cnn);
	for (auto _ : st)
		benchmark::DoNotOptimize(cnn.plan(p.u, p.goals, p.start).cost);
}
BENCHMARK(BM_PlanCnn)->Unit(benchmark::kMillisecond);

void BM_PlanDijkstra(benchmark::State& st)
{
	const auto& p = washbasinPlan();
	for (auto _ : st)
		benchmark::DoNotOptimize(
		    DijkstraPlanner::costField(p.u, p.goals).data());
}
BENCHMARK(BM_PlanDijkstra)->Unit(benchmark::kMillisecond);

void BM_PlanDijkstraEarlyStop(benchmark::State& st)
{
	const auto& p = washbasinPlan();
	for (auto _ : st)
		benchmark::DoNotOptimize(
		    DijkstraPlanner::plan(p.u, p.goals, p.start).cost);
}
BENCHMARK(BM_PlanDijkstraEarlyStop)->Unit(benchmark::kMillisecond);

void BM_Traversability(benchmark::State& st)
{
	auto& f = fixture();
	const SemanticPlanner planner(f.map, f.config.cnn, f.config.traversability);
	for (auto _ : st)
		benchmark::DoNotOptimize(
		    planner.traversability(f.nav->profile()).values().data());
}
BENCHMARK(BM_Traversability)->Unit(benchmark::kMillisecond);
}  // namespace

BENCHMARK_MAIN();
