/* semnav: semantic navigation from tilting-laser sweeps */
// Perception stages on one 211 x 361 sweep (the paper's LMS200 on a tilting
// head: theta -15..90 deg, phi -90..90 deg, 0.5 deg), each stage and the
// whole pipeline; and, as a baseline, normals by per-pixel PCA over the
// 3 x 3 neighbourhood. Prints the medians and the PCA / NormalImage ratio.
// BM_Total runs the widest SIMD kernels the CPU has (libs/perception
// SimdKernels.h), BM_TotalBaselineKernels the portable (SSE2) ones.
//
// The sweep is a synthetic office room (tests/perception/SyntheticScene.h,
// 5 mm range noise), or sweep SEMNAV_BENCH_SWEEP (default 0) of the rawlog
// named by SEMNAV_BENCH_RAWLOG, e.g. one written by semnav-sim.
//   build/tests/bench/bench_perception            (7 repetitions, medians)
//   SEMNAV_BENCH_RAWLOG=out/sim/office.rawlog
//   build/tests/bench/bench_perception
// BM_TotalEverySweep cycles through all of the rawlog's sweeps (the mean
// per sweep, as semnav-perceive streams them).
#include <benchmark/benchmark.h>
#include <semnav/perception/PerceptionPipeline.h>
#include <semnav/scan/RawlogSweepReader.h>

#include <Eigen/Dense>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>

#include "../../libs/perception/src/SimdKernels.h"
#include "../perception/SyntheticScene.h"

using namespace semnav;

namespace
{
Sweep makeSweep()
{
	if (const char* path = std::getenv("SEMNAV_BENCH_RAWLOG"))
	{
		const char* k = std::getenv("SEMNAV_BENCH_SWEEP");
		const int want = k ? std::atoi(k) : 0;
		RawlogSweepReader reader(path);
		Sweep s;
		for (int i = 0; reader.next(s); i++)
			if (i == want) return s;
		std::fprintf(
		    stderr, "bench_perception: %s has no sweep %d\n", path, want);
		std::exit(1);
	}
	// An office-like room: walls, ceiling, a recessed door, furniture.
	test::SynthScene sc = test::boxRoom(-2, 6, -2.5, 3, 2.7);
	sc.noise = 0.005;
	sc.boxes.push_back({{2.0, 2.98, 0}, {2.96, 3.02, 2.0}, Label::Door});
	sc.boxes.push_back({{1.5, -1.5, 0}, {3.1, -0.7, 0.75}, Label::Obstacle});
	sc.boxes.push_back({{5.5, -1.0, 0}, {6.0, 0.2, 1.8}, Label::Obstacle});
	sc.boxes.push_back({{3.5, 1.0, 0}, {3.8, 1.3, 0.4}, Label::Obstacle});
	return test::renderSweep(sc);
}

const Sweep& sweep()
{
	static const Sweep s = makeSweep();
	return s;
}

/** The stages' outputs, computed once, as inputs of the later stages. */
struct Stages
{
	NormalImage normals;
	RangeSegmentation segmentation;
	Roughness roughness;
	Stages()
	{
		normals.compute(sweep());
		segmentation.compute(sweep());
		roughness.compute(normals, segmentation.areaIds());
	}
};
const Stages& stages()
{
	static const Stages s;
	return s;
}

void BM_NormalImage(benchmark::State& st)
{
	NormalImage ni;
	for (auto _ : st)
	{
		ni.compute(sweep());
		benchmark::DoNotOptimize(ni.normals().data);
	}
}
BENCHMARK(BM_NormalImage)->Unit(benchmark::kMillisecond);

void BM_RangeSegmentation(benchmark::State& st)
{
	RangeSegmentation seg;
	for (auto _ : st)
	{
		seg.compute(sweep());
		benchmark::DoNotOptimize(seg.areaIds().data);
	}
	st.counters["areas"] = seg.areaCount();
}
BENCHMARK(BM_RangeSegmentation)->Unit(benchmark::kMillisecond);

void BM_Roughness(benchmark::State& st)
{
	Roughness r;
	for (auto _ : st)
	{
		r.compute(stages().normals, stages().segmentation.areaIds());
		benchmark::DoNotOptimize(r.rBar().data);
	}
}
BENCHMARK(BM_Roughness)->Unit(benchmark::kMillisecond);

void BM_RuleClassifier(benchmark::State& st)
{
	RuleClassifier rc;
	LabeledSweep out;
	for (auto _ : st)
	{
		rc.classify(
		    stages().normals, stages().segmentation.areaIds(),
		    stages().roughness, out);
		benchmark::DoNotOptimize(out.labels.data);
	}
	st.counters["regions"] = static_cast<double>(out.regions.size());
}
BENCHMARK(BM_RuleClassifier)->Unit(benchmark::kMillisecond);

void BM_Total(benchmark::State& st)
{
	PerceptionPipeline pipeline;
	LabeledSweep out;
	for (auto _ : st)
	{
		pipeline.process(sweep(), out);
		benchmark::DoNotOptimize(out.labels.data);
	}
}
BENCHMARK(BM_Total)->Unit(benchmark::kMillisecond);

/** The pipeline with the portable (SSE2) builds of the SIMD kernels, as on
 * a CPU without AVX2. */
void BM_TotalBaselineKernels(benchmark::State& st)
{
	detail::setKernelsBaselineOnly(true);
	PerceptionPipeline pipeline;
	LabeledSweep out;
	for (auto _ : st)
	{
		pipeline.process(sweep(), out);
		benchmark::DoNotOptimize(out.labels.data);
	}
	detail::setKernelsBaselineOnly(false);
}
BENCHMARK(BM_TotalBaselineKernels)->Unit(benchmark::kMillisecond);

/** Every sweep of SEMNAV_BENCH_RAWLOG (without it, the bench's sweep). */
const std::vector<Sweep>& everySweep()
{
	static const std::vector<Sweep> all = []
	{
		std::vector<Sweep> v;
		if (const char* path = std::getenv("SEMNAV_BENCH_RAWLOG"))
		{
			RawlogSweepReader reader(path);
			Sweep s;
			while (reader.next(s)) v.push_back(s);
		}
		if (v.empty()) v.push_back(sweep());
		return v;
	}();
	return all;
}

/** The pipeline over every sweep of the rawlog in turn, one sweep per
 * iteration, as semnav-perceive streams them (each sweep's data cold):
 * the mean time per sweep. */
void BM_TotalEverySweep(benchmark::State& st)
{
	const std::vector<Sweep>& all = everySweep();
	PerceptionPipeline pipeline;
	LabeledSweep out;
	for (const Sweep& s : all) pipeline.process(s, out);  // buffers grown
	std::size_t k = 0;
	for (auto _ : st)
	{
		pipeline.process(all[k], out);
		benchmark::DoNotOptimize(out.labels.data);
		k = (k + 1) % all.size();
	}
	st.counters["sweeps"] = static_cast<double>(all.size());
}
BENCHMARK(BM_TotalEverySweep)->Unit(benchmark::kMillisecond);

/** Baseline: normal = eigenvector of the smallest eigenvalue of the 3 x 3
 * neighbourhood's covariance, turned toward the sensor. */
void BM_PcaNormals3x3(benchmark::State& st)
{
	const cv::Mat& P = stages().normals.points();
	const cv::Mat& M = stages().normals.pointMask();
	const auto& S = stages().normals.sensorPositions();
	cv::Mat out(P.size(), CV_32FC3);
	for (auto _ : st)
	{
		for (int r = 0; r < P.rows; r++)
			for (int c = 0; c < P.cols; c++)
			{
				out.at<cv::Vec3f>(r, c) = cv::Vec3f(0, 0, 0);
				if (!M.at<uint8_t>(r, c)) continue;
				Eigen::Vector3f sum = Eigen::Vector3f::Zero();
				Eigen::Matrix3f sq = Eigen::Matrix3f::Zero();
				int n = 0;
				for (int rr = std::max(0, r - 1);
				     rr <= std::min(P.rows - 1, r + 1); rr++)
					for (int cc = std::max(0, c - 1);
					     cc <= std::min(P.cols - 1, c + 1); cc++)
					{
						if (!M.at<uint8_t>(rr, cc)) continue;
						const cv::Vec3f& q = P.at<cv::Vec3f>(rr, cc);
						const Eigen::Vector3f v(q[0], q[1], q[2]);
						sum += v;
						sq += v * v.transpose();
						n++;
					}
				if (n < 3) continue;
				const Eigen::Vector3f mean = sum / n;
				const Eigen::Matrix3f cov = sq / n - mean * mean.transpose();
				Eigen::SelfAdjointEigenSolver<Eigen::Matrix3f> es;
				es.computeDirect(cov);
				Eigen::Vector3f nrm = es.eigenvectors().col(0);
				const cv::Vec3f& p = P.at<cv::Vec3f>(r, c);
				const cv::Vec3f toS = S[r] - p;
				if (nrm.x() * toS[0] + nrm.y() * toS[1] + nrm.z() * toS[2] < 0)
					nrm = -nrm;
				out.at<cv::Vec3f>(r, c) = cv::Vec3f(nrm.x(), nrm.y(), nrm.z());
			}
		benchmark::DoNotOptimize(out.data);
	}
}
BENCHMARK(BM_PcaNormals3x3)->Unit(benchmark::kMillisecond);

/** Console output plus the medians, kept for the summary. */
class Reporter : public benchmark::ConsoleReporter
{
public:
	std::map<std::string, double> median, medianCpu;  // ms
	void ReportRuns(const std::vector<Run>& runs) override
	{
		for (const auto& r : runs)
		{
			const std::string name = r.benchmark_name();
			const auto pos = name.find("_median");
			const std::string key =
			    pos != std::string::npos ? name.substr(0, pos) : name;
			if (pos != std::string::npos || r.repetitions <= 1)
			{
				median[key] = r.GetAdjustedRealTime();
				medianCpu[key] = r.GetAdjustedCPUTime();
			}
		}
		ConsoleReporter::ReportRuns(runs);
	}
};
}  // namespace

int main(int argc, char** argv)
{
	std::vector<char*> args(argv, argv + argc);
	bool repetitions = false;
	for (int i = 1; i < argc; i++)
		repetitions |=
		    std::strncmp(argv[i], "--benchmark_repetitions", 23) == 0;
	static char rep[] = "--benchmark_repetitions=7";
	static char agg[] = "--benchmark_report_aggregates_only=true";
	if (!repetitions)
	{
		args.push_back(rep);
		args.push_back(agg);
	}
	int n = static_cast<int>(args.size());
	benchmark::Initialize(&n, args.data());
	std::printf(
	    "sweep: %zu x %zu, %zu valid pixels (%s)\n", sweep().rows(),
	    sweep().cols(), sweep().validCount(),
	    std::getenv("SEMNAV_BENCH_RAWLOG") ? std::getenv("SEMNAV_BENCH_RAWLOG")
	                                       : "synthetic office room");
	Reporter reporter;
	benchmark::RunSpecifiedBenchmarks(&reporter);
	const auto& m = reporter.median;
	const auto& mc = reporter.medianCpu;
	std::printf("medians, ms (wall / cpu):\n");
	for (const char* b :
	     {"BM_NormalImage", "BM_RangeSegmentation", "BM_Roughness",
	      "BM_RuleClassifier", "BM_Total", "BM_TotalBaselineKernels",
	      "BM_TotalEverySweep", "BM_PcaNormals3x3"})
		if (m.count(b))
			std::printf("  %-22s %7.3f / %7.3f\n", b, m.at(b), mc.at(b));
	if (m.count("BM_NormalImage") && m.count("BM_PcaNormals3x3"))
		std::printf(
		    "normals: paper's 4-neighbour cross products %.3f ms, 3x3 PCA %.3f "
		    "ms: "
		    "PCA / NormalImage = %.1f (cpu %.1f)\n",
		    m.at("BM_NormalImage"), m.at("BM_PcaNormals3x3"),
		    m.at("BM_PcaNormals3x3") / m.at("BM_NormalImage"),
		    mc.at("BM_PcaNormals3x3") / mc.at("BM_NormalImage"));
	if (m.count("BM_Total"))
		std::printf(
		    "total per sweep (median): %.3f ms wall, %.3f ms cpu (budget 5 "
		    "ms), SIMD kernels: %s\n",
		    m.at("BM_Total"), mc.at("BM_Total"), detail::simdKernels().name);
	benchmark::Shutdown();
	return 0;
}
