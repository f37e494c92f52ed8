/* semnav: semantic navigation from tilting-laser sweeps */
// Haar cascade detection (issue 4): all three cascades (washbasin,
// wastebasket, stairs) on one 211 x 361 simulated sweep, as configured in
// config/cascade.ini (panoramic image, near + far passes, 3D size check),
// against baselines in the same run: the same cascades without the far
// (upscaled) passes, and OpenCV's own frontal-face Haar cascade on the same
// image. Perception (normals, labels) runs once, outside the timing. Run
//   bench_detection --benchmark_repetitions=5
//   --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <semnav/detection/CascadeDetector.h>
#include <semnav/detection/GroundTruthObject.h>
#include <semnav/perception/PerceptionPipeline.h>
#include <semnav/sim/RayCaster.h>
#include <semnav/sim/SceneLoader.h>
#include <semnav/sim/SimulationRunner.h>
#include <semnav/sim/TiltingLaserSimulator.h>

#include <filesystem>
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

void runDetector(benchmark::State& state, CascadeDetector::TOptions opts)
{
	const Input& in = input();
	for (const auto& k : opts.classes)
		if (!std::filesystem::exists(opts.cascadePath(k)))
		{
			state.SkipWithError("cascades missing: run scripts/train-cascades");
			return;
		}
	CascadeDetector det(opts);
	std::size_t found = 0;
	for (auto _ : state)
	{
		const auto c = det.detectCandidates(
		    in.sweep.phis(), in.sweep.thetas(), in.labeled.normals,
		    in.labeled.normalMask, in.labeled.points, in.labeled.groundZ,
		    in.labeled.labels);
		found = 0;
		for (const auto& x : c) found += x.accepted;
		benchmark::DoNotOptimize(found);
	}
	state.counters["detections"] = double(found);
	state.counters["gt_objects"] = double(in.objects);
	state.counters["rows"] = double(in.sweep.rows());
	state.counters["cols"] = double(in.sweep.cols());
}

/** All three cascades as shipped (near + far passes). */
void BM_ThreeCascades(benchmark::State& s)
{
	runDetector(s, shipped());
}

/** Baseline: the same cascades without the far (upscaled) passes. */
void BM_ThreeCascadesNoUpscaling(benchmark::State& s)
{
	auto o = shipped();
	for (auto& k : o.classes) k.farUpscale = 0;
	runDetector(s, o);
}

/** Reference: OpenCV's frontal-face Haar cascade (opencv-data) on the same
 * detection image, detectMultiScale(1.1, 3). */
void BM_OpenCvFaceCascade(benchmark::State& state)
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
	for (auto _ : state)
	{
		cc.detectMultiScale(img, found, 1.1, 3);
		benchmark::DoNotOptimize(found.data());
	}
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
BENCHMARK(BM_ThreeCascadesNoUpscaling)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_OpenCvFaceCascade)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_DetectionImage)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_MAIN();
