/* semnav: semantic navigation from tilting-laser sweeps */
// Haar cascade detection (issue 4): all three cascades (washbasin,
// wastebasket, stairs) on one 211 x 361 simulated sweep (panoramic image,
// near + far passes, 3D size check): as configured in config/cascade.ini
// (range_scales: every window at the scales its range allows, around
// object points; also with the evaluator's portable loop instead of AVX2),
// without the object-point condition, with object proposals
// (windows around the regions the rule classifier left to objects, at the sizes
// the class can have there) and over the whole image (the paper's search, as
// before the proposals), against baselines in the same run: the whole-image
// search without the far (upscaled) passes and OpenCV's own frontal-face Haar
// cascade on the same image. BM_CascadeSearch times the three cascades'
// search alone (detection and range images made outside the timing, no 3D
// check) beside OpenCV's detectMultiScale with the same three XMLs
// (BM_OpenCvSameCascades) and beside that face cascade. Perception (normals,
// labels) runs once, outside the timing. The shipped configuration searches the
// three classes in parallel (threads = 0: both cores here);
// BM_ThreeCascadesOneThread is the same on one thread. The counters split the
// detector's time (ms, cascades and checks summed over the classes' threads):
// detection image, proposals, cascades, 3D size check. At the end the medians
// (or means without repetitions) are compared. Run
//   bench_detection --benchmark_repetitions=5
//   --benchmark_report_aggregates_only=true
// (OPENCV_FOR_THREADS_NUM=1 for one thread: detectMultiScale is parallel).
#include <benchmark/benchmark.h>
#include <semnav/detection/CascadeDetector.h>
#include <semnav/perception/PerceptionPipeline.h>
#include <semnav/sim/RayCaster.h>
#include <semnav/sim/SceneLoader.h>
#include <semnav/sim/SimulationRunner.h>
#include <semnav/sim/TiltingLaserSimulator.h>
#include <semnav/training/GroundTruthObject.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <initializer_list>
#include <map>
#include <opencv2/core/utility.hpp>
#include <opencv2/objdetect.hpp>
#include <string>

using namespace semnav;

namespace
{
const std::string kSource = SEMNAV_SOURCE_DIR;

struct Input
{
	Sweep sweep;
	LabeledSweep labeled;
	std::size_t objects = 0;
};

/** The sweep of datasets/cascade-scenes/test_a.yaml (a held-out scene)
 * that shows the most washbasins, wastebaskets and stairs. */
const Input& input()
{
	static const Input in = []
	{
		const Scene scene = SceneLoader::loadFile(
		    kSource + "/datasets/cascade-scenes/test_a.yaml");
		RayCaster rc(scene, 1);
		TiltingLaserSimulator sim(rc, scene.sensor, 1);
		Input best;
		for (std::size_t k = 0; k < scene.trajectory.size(); k++)
		{
			const auto sw = sim.simulate(
			    scene.trajectory[k], k, SimulationRunner::epoch(), 1 / 37.5);
			const auto objs = GroundTruthObject::fromLabelImage(
			    sw.labels,
			    {Label::Washbasin, Label::Wastebasket, Label::Stairs});
			std::size_t n = 0;
			for (const auto& o : objs) n += o.pixels >= 150;
			if (k == 0 || n > best.objects)
			{
				best.sweep = sw.toSweep();
				best.objects = n;
			}
		}
		PerceptionPipeline p;
		best.labeled = p.process(best.sweep);
		return best;
	}();
	return in;
}

CascadeDetector::TOptions shipped()
{
	return CascadeDetector::TOptions::fromIniFile(
	    kSource + "/config/cascade.ini");
}

/** Whether every class's cascade file exists (else the benchmark is
 * skipped with an error). */
bool cascadesPresent(
    benchmark::State& state, const CascadeDetector::TOptions& opts)
{
	for (const auto& k : opts.classes)
		if (!std::filesystem::exists(opts.cascadePath(k)))
		{
			state.SkipWithError("cascades missing: run scripts/train-cascades");
			return false;
		}
	return true;
}

void runDetector(
    benchmark::State& state, CascadeDetector::TOptions opts, bool simd = true)
{
	const Input& in = input();
	if (!cascadesPresent(state, opts)) return;
	CascadeDetector det(opts);
	det.setSimd(simd);
	std::size_t found = 0;
	CascadeDetector::Timings sum;
	double n = 0;
	for (auto _ : state)
	{
		const auto c = det.detectCandidates(
		    in.sweep.phis(), in.sweep.thetas(), in.labeled.normals,
		    in.labeled.normalMask, in.labeled.points, in.labeled.groundZ,
		    in.labeled.labels, in.labeled.areaIds);
		found = 0;
		for (const auto& x : c) found += x.accepted;
		benchmark::DoNotOptimize(found);
		const auto& t = det.lastTimings();
		sum.image += t.image;
		sum.proposals += t.proposals;
		sum.cascades += t.cascades;
		sum.sizeCheck += t.sizeCheck;
		n++;
	}
	if (n > 0)
	{
		state.counters["ms_image"] = sum.image / n;
		state.counters["ms_proposals"] = sum.proposals / n;
		state.counters["ms_cascades"] = sum.cascades / n;
		state.counters["ms_size_check"] = sum.sizeCheck / n;
	}
	std::size_t proposals = 0;
	for (const auto& ps : det.lastProposals()) proposals += ps.size();
	state.counters["proposals"] = double(proposals);
	state.counters["detections"] = double(found);
	state.counters["gt_objects"] = double(in.objects);
	state.counters["rows"] = double(in.sweep.rows());
	state.counters["cols"] = double(in.sweep.cols());
}

/** All three cascades as shipped (config/cascade.ini: range_scales, the
 * whole image searched at the scales each window's range allows). */
void BM_ThreeCascades(benchmark::State& s)
{
	runDetector(s, shipped());
}

/** Baseline: the shipped search with the classes one after another on one
 * thread (threads = 1) instead of each on its own (threads = 0, all cores):
 * the same candidates. */
void BM_ThreeCascadesOneThread(benchmark::State& s)
{
	auto o = shipped();
	o.threads = 1;
	runDetector(s, o);
}

/** The shipped search with the evaluator's portable loop instead of AVX2
 * (CascadeDetector::setSimd(false)): the same candidates. */
void BM_ThreeCascadesPortable(benchmark::State& s)
{
	runDetector(s, shipped(), false);
}

/** All three cascades with object proposals (proposals = true). */
void BM_ThreeCascadesProposals(benchmark::State& s)
{
	auto o = shipped();
	o.proposals = true;
	runDetector(s, o);
}

/** Baseline: the same cascades over the whole image (every window of the
 * near and far passes, detectMultiScale), as before the proposals and the
 * range-gated search. */
void BM_ThreeCascadesWholeImage(benchmark::State& s)
{
	auto o = shipped();
	o.proposals = false;
	o.rangeScales = false;
	runDetector(s, o);
}

/** The range-gated search without the object-point condition
 * (range_objects_only = false): windows at the scales their range allows,
 * anywhere. */
void BM_ThreeCascadesRangeScalesAnywhere(benchmark::State& s)
{
	auto o = shipped();
	o.proposals = false;
	o.rangeScales = true;
	o.rangeObjectsOnly = false;
	runDetector(s, o);
}

/** Baseline: the whole-image search without the far (upscaled) passes. */
void BM_ThreeCascadesWholeImageNoUpscaling(benchmark::State& s)
{
	auto o = shipped();
	o.proposals = false;
	o.rangeScales = false;
	for (auto& k : o.classes) k.farUpscale = 0;
	runDetector(s, o);
}

/** The detection and range images of input() for `det`'s search (no
 * segments), made once outside the timing. */
CascadeDetector::SearchInput prepareSearch(CascadeDetector& det)
{
	const Input& in = input();
	return det.prepareSearch(
	    in.sweep.phis(), in.sweep.thetas(), in.labeled.normals,
	    in.labeled.normalMask, in.labeled.points, in.labeled.groundZ,
	    in.labeled.labels, in.labeled.areaIds, false);
}

/** The three cascades' search alone (CascadeDetector::searchCascades: the
 * shipped range-gated passes on `threads`), on detection and range images
 * made once outside the timing: the boxes before any 3D check. */
void runCascadeSearch(benchmark::State& state, int threads)
{
	auto opts = shipped();
	opts.threads = threads;
	if (!cascadesPresent(state, opts)) return;
	CascadeDetector det(opts);
	const auto search = prepareSearch(det);
	std::size_t boxes = 0;
	for (auto _ : state)
	{
		const auto found = det.searchCascades(search);
		boxes = 0;
		for (const auto& c : found) boxes += c.boxes.size();
		benchmark::DoNotOptimize(boxes);
	}
	state.counters["boxes"] = double(boxes);
}

/** The cascades' search alone, as shipped (both cores here). */
void BM_CascadeSearch(benchmark::State& s)
{
	runCascadeSearch(s, 0);
}

/** The same on one thread. */
void BM_CascadeSearchOneThread(benchmark::State& s)
{
	runCascadeSearch(s, 1);
}

/** Reference: OpenCV's cv::CascadeClassifier::detectMultiScale with the
 * shipped XMLs (the same first max_stages stages, read by OpenCV), on the
 * same detection images, bands, zero borders, scale factor, min neighbours
 * and window size limits as the search (CascadeDetector::runCascade
 * without range_scales): every window at every scale, OpenCV's window
 * steps (stairs' window_step 2 is not OpenCV's), the classes one after
 * another, each detectMultiScale on OpenCV's threads (`threads` -1) or on
 * one. */
void runOpenCvSameCascades(benchmark::State& state, int threads)
{
	auto opts = shipped();
	opts.rangeScales = false;
	if (!cascadesPresent(state, opts)) return;
	CascadeDetector det(opts);
	const auto search = prepareSearch(det);
	std::vector<cv::Rect> boxes;
	std::vector<int> neighbours;
	std::size_t found = 0;
	const int before = cv::getNumThreads();
	cv::setNumThreads(threads);
	for (auto _ : state)
	{
		found = 0;
		for (std::size_t i = 0; i < opts.classes.size(); i++)
		{
			det.runCascade(
			    i, search.images.at(opts.channelOf(opts.classes[i])), boxes,
			    neighbours);
			found += boxes.size();
		}
		benchmark::DoNotOptimize(found);
	}
	cv::setNumThreads(before);
	state.counters["boxes"] = double(found);
}

void BM_OpenCvSameCascades(benchmark::State& s)
{
	runOpenCvSameCascades(s, -1);
}

void BM_OpenCvSameCascadesOneThread(benchmark::State& s)
{
	runOpenCvSameCascades(s, 1);
}

/** Reference: OpenCV's frontal-face Haar cascade (opencv-data) on the same
 * detection image, detectMultiScale(1.1, 3), on OpenCV's threads (all
 * cores), or on one. */
void runOpenCvFaceCascade(benchmark::State& state, int threads)
{
	const std::string face =
	    "/usr/share/opencv4/haarcascades/haarcascade_frontalface_default.xml";
	cv::CascadeClassifier cc;
	if (!std::filesystem::exists(face) || !cc.load(face))
	{
		state.SkipWithError("opencv-data is not installed");
		return;
	}
	const Input& in = input();
	auto opts = shipped();
	opts.classes.clear();
	CascadeDetector det(opts);
	const cv::Mat img = det.detectionImage(
	    in.sweep.phis(), in.sweep.thetas(), in.labeled.normals,
	    in.labeled.normalMask);
	std::vector<cv::Rect> found;
	const int before = cv::getNumThreads();
	cv::setNumThreads(threads);
	for (auto _ : state)
	{
		cc.detectMultiScale(img, found, 1.1, 3);
		benchmark::DoNotOptimize(found.data());
	}
	cv::setNumThreads(before);
}

void BM_OpenCvFaceCascade(benchmark::State& s)
{
	runOpenCvFaceCascade(s, -1);
}

void BM_OpenCvFaceCascadeOneThread(benchmark::State& s)
{
	runOpenCvFaceCascade(s, 1);
}

/** The detection image alone (normal smoothing, grey, panoramic). */
void BM_DetectionImage(benchmark::State& state)
{
	const Input& in = input();
	auto opts = shipped();
	opts.classes.clear();
	CascadeDetector det(opts);
	for (auto _ : state)
	{
		const cv::Mat img = det.detectionImage(
		    in.sweep.phis(), in.sweep.thetas(), in.labeled.normals,
		    in.labeled.normalMask);
		benchmark::DoNotOptimize(img.data);
	}
}
}  // namespace

BENCHMARK(BM_ThreeCascades)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ThreeCascadesOneThread)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_ThreeCascadesPortable)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_ThreeCascadesProposals)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_ThreeCascadesWholeImage)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_ThreeCascadesRangeScalesAnywhere)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_ThreeCascadesWholeImageNoUpscaling)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_CascadeSearch)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_CascadeSearchOneThread)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_OpenCvSameCascades)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_OpenCvSameCascadesOneThread)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_OpenCvFaceCascade)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_OpenCvFaceCascadeOneThread)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_DetectionImage)->Unit(benchmark::kMillisecond)->UseRealTime();
namespace
{
/** The console output, and each benchmark's median real time (the mean
 * when run without repetitions) for the comparison at the end. */
class RatioReporter : public benchmark::ConsoleReporter
{
public:
	RatioReporter()
	    : benchmark::ConsoleReporter(
	          isatty(fileno(stdout)) ? OO_Defaults : OO_Tabular)
	{
	}
	std::map<std::string, double> ms;
	void ReportRuns(const std::vector<Run>& runs) override
	{
		for (const auto& r : runs)
		{
			const std::string name = r.run_name.function_name;
			const double t = r.GetAdjustedRealTime();  // in the unit: ms
			// Aggregates follow their repetitions: the median wins.
			if (r.run_type == Run::RT_Iteration || r.aggregate_name == "median")
				ms[name] = t;
		}
		ConsoleReporter::ReportRuns(runs);
	}
};
}  // namespace

int main(int argc, char** argv)
{
	benchmark::Initialize(&argc, argv);
	if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
	RatioReporter rep;
	benchmark::RunSpecifiedBenchmarks(&rep);
	benchmark::Shutdown();
	const auto has = [&](const char* n) { return rep.ms.count(n) > 0; };
	struct Comparison
	{
		const char *ours, *theirs, *what;
	};
	for (const auto& c : std::initializer_list<Comparison>{
	         {"BM_CascadeSearch", "BM_OpenCvSameCascades",
	          "OpenCV's detectMultiScale with the same three XMLs"},
	         {"BM_CascadeSearchOneThread", "BM_OpenCvSameCascadesOneThread",
	          "OpenCV's detectMultiScale with the same three XMLs"},
	         {"BM_CascadeSearch", "BM_OpenCvFaceCascade",
	          "OpenCV's face cascade on the same image"},
	         {"BM_CascadeSearchOneThread", "BM_OpenCvFaceCascadeOneThread",
	          "OpenCV's face cascade on the same image"}})
		if (has(c.ours) && has(c.theirs))
			std::printf(
			    "%s: the three cascades' search %.2f ms, %.2f times %s "
			    "(%.2f ms)\n",
			    c.ours, rep.ms.at(c.ours),
			    rep.ms.at(c.ours) / rep.ms.at(c.theirs), c.what,
			    rep.ms.at(c.theirs));
	const char* base = "BM_ThreeCascadesWholeImage";
	if (!has(base)) return 0;
	std::printf("\nmedian real time, ms (ratio to the whole-image search):\n");
	for (const auto& [name, t] : rep.ms)
		std::printf(
		    "  %-40s %8.2f  (%.2f)\n", name.c_str(), t, t / rep.ms.at(base));
	if (has("BM_ThreeCascadesProposals"))
		std::printf(
		    "proposals: %.1f times faster than the whole-image search\n",
		    rep.ms.at(base) / rep.ms.at("BM_ThreeCascadesProposals"));
	if (has("BM_ThreeCascades"))
		std::printf(
		    "shipped (range_scales): %.1f times faster than the whole-image "
		    "search\n",
		    rep.ms.at(base) / rep.ms.at("BM_ThreeCascades"));
	if (has("BM_ThreeCascades") && has("BM_ThreeCascadesOneThread"))
		std::printf(
		    "shipped, classes in parallel: %.2f times faster than on one "
		    "thread\n",
		    rep.ms.at("BM_ThreeCascadesOneThread") /
		        rep.ms.at("BM_ThreeCascades"));
	return 0;
}
