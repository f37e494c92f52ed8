/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/config/CConfigFileBase.h>
#include <omp.h>
#include <semnav/cascade/CascadeError.h>
#include <semnav/cascade/CascadeEvaluator.h>
#include <semnav/cascade/CascadeTrainer.h>
#include <semnav/cascade/IntegralImages.h>
#include <semnav/common/OptionTable.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <numeric>
#include <opencv2/imgproc.hpp>
#include <set>

#include "CompiledFeature.h"
#include "Random.h"
#include "StageTrainer.h"

namespace semnav
{
// ---------------------------------------------------------------- options
namespace
{
using O = CascadeTrainer::TOptions;
const OptionTable<O>& optionTable()
{
	static const auto t =
	    OptionTable<O>()
	        .integer(
	            "window_width", &O::windowWidth, 8, 64,
	            "Training window width (pixels).")
	        .integer(
	            "window_height", &O::windowHeight, 8, 64,
	            "Training window height (pixels).")
	        .named(
	            "feature_mode", &O::mode, haarModeFromName, haarModeName,
	            "BASIC | CORE | ALL (ALL: with 45-degree features).")
	        .integer("num_stages", &O::numStages, 1, 100, "Most stages.")
	        .real(
	            "min_hit_rate", &O::minHitRate, 0.5, 1.0,
	            "Each stage keeps this share of the positives.")
	        .real(
	            "calibration_fraction", &O::calibrationFraction, 0.0, 0.9,
	            "Share of positives held out to set stage thresholds; 0: "
	            "off.")
	        .real(
	            "max_false_alarm", &O::maxFalseAlarm, 0.01, 0.99,
	            "Each stage accepts at most this share of negatives.")
	        .real(
	            "target_false_alarm", &O::targetFalseAlarm, 0.0, 1.0,
	            "Stop at this overall false alarm rate (0: max_false_alarm "
	            "^ num_stages).")
	        .integer(
	            "max_weak_count", &O::maxWeakCount, 1, 10000,
	            "Most stumps per stage.")
	        .real(
	            "weight_trim_rate", &O::weightTrimRate, 0.5, 1.0,
	            "Boosting weight trimming.")
	        .integer(
	            "negatives_per_stage", &O::negativesPerStage, 10, 1000000,
	            "Negative windows per stage.")
	        .integer(
	            "feature_bins", &O::featureBins, 2, 256,
	            "Histogram bins of a feature's values.")
	        .real(
	            "feature_fraction", &O::featureFraction, 0.001, 1.0,
	            "Share of the feature pool drawn per stage (1: all).")
	        .real(
	            "round_feature_fraction", &O::roundFeatureFraction, 0.001, 1.0,
	            "Share of those tried for each stump.")
	        .real(
	            "negative_scale_factor", &O::negativeScaleFactor, 1.01, 4.0,
	            "Pyramid step for negative windows.")
	        .real(
	            "negative_max_iou", &O::negativeMaxIou, 0.0, 1.0,
	            "Negatives overlap objects at most this much.")
	        .integer(
	            "min_negatives", &O::minNegatives, 1, 1000000,
	            "Stop when fewer negative windows are still accepted.")
	        .integer(
	            "threads", &O::threads, 0, 1024,
	            "OpenMP threads, 0 = all cores (same results).");
	return t;
}
}  // namespace

const std::vector<std::string>& CascadeTrainer::TOptions::knownKeys()
{
	static const std::vector<std::string> keys = optionTable().keys();
	return keys;
}

SEMNAV_OPTIONS_FROM_TABLE(CascadeTrainer::TOptions, optionTable())

CascadeTrainer::CascadeTrainer() : CascadeTrainer(TOptions()) {}

CascadeTrainer::CascadeTrainer(const TOptions& options)
    : mrpt::system::COutputLogger("CascadeTrainer"), m_options(options)
{
	logging_enable_console_output = false;
}

// --------------------------------------------------------------- helpers
namespace
{
using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t0)
{
	return std::chrono::duration<double>(Clock::now() - t0).count();
}
using detail::SampleSet;
using detail::StageTrainer;

/** One pyramid level of a negative image. */
struct Level
{
	int image = 0;
	double scale = 1;
	cv::Mat img;
	int nx = 0, ny = 0;
	/** With a range gate: per visited position (step 2 below scale 2,
	 * row-major over the visited ones), whether it may be a negative. */
	std::vector<uint8_t> allowed;
	int step() const { return scale >= 2 ? 1 : 2; }
	bool isAllowed(int x, int y) const
	{
		if (allowed.empty()) return true;
		const int s = step(), cols = (nx + s - 1) / s;
		return allowed[std::size_t(y / s) * std::size_t(cols) + x / s] != 0;
	}
	std::size_t windows() const { return std::size_t(nx) * std::size_t(ny); }
};

double iou(const cv::Rect2d& a, const cv::Rect2d& b)
{
	const double i = (a & b).area();
	const double u = a.area() + b.area() - i;
	return u > 0 ? i / u : 0;
}

struct MiningResult
{
	std::vector<cv::Mat> windows;
	std::size_t tried = 0, accepted = 0;
	double acceptanceRatio() const
	{
		return tried ? double(accepted) / double(tried) : 0.0;
	}
};

/** Windows the cascade accepts among all windows of all pyramid levels
 * (at the positions detectMultiScale visits: every 2nd below scale 2,
 * every one above; not those excluded): a first pass counts them per
 * level, `wanted` of them are drawn at random (seeded; all when there are
 * fewer), a second pass cuts those out. Levels run in parallel; results are
 * merged in level order, so they do not depend on the thread count. */
MiningResult mineNegatives(
    const HaarCascade& cascade, const std::vector<Level>& levels,
    const std::vector<NegativeImage>& negatives, double maxIou,
    std::size_t wanted, detail::Random& rng, int threads)
{
	MiningResult res;
	const cv::Size win = cascade.windowSize;
	const std::size_t L = levels.size();
	std::vector<std::size_t> accepted(L, 0), tried(L, 0);
	// Scans one level; calls take(localRank, x, y) for accepted windows.
	const auto scan = [&](std::size_t l, CascadeEvaluator& ev, const auto& take)
	{
		const Level& lv = levels[l];
		const auto& excl = negatives[lv.image].exclude;
		ev.setImage(lv.img);
		std::size_t rank = 0, n = 0;
		// The positions detectMultiScale evaluates: step 2 below scale 2.
		const int step = lv.scale >= 2 ? 1 : 2;
		for (int y = 0; y < lv.ny; y += step)
			for (int x = 0; x < lv.nx; x += step)
			{
				if (!lv.isAllowed(x, y)) continue;
				if (!excl.empty())
				{
					const cv::Rect2d box(
					    x * lv.scale, y * lv.scale, win.width * lv.scale,
					    win.height * lv.scale);
					bool skip = false;
					for (const auto& e : excl)
						if (iou(box, cv::Rect2d(e)) > maxIou)
						{
							skip = true;
							break;
						}
					if (skip) continue;
				}
				n++;
				if (ev.accepted(ev.evaluate({x, y}))) take(rank++, x, y);
			}
		return std::make_pair(rank, n);
	};
#pragma omp parallel num_threads(threads)
	{
		CascadeEvaluator ev(cascade);
#pragma omp for schedule(dynamic, 1)
		for (std::size_t l = 0; l < L; l++)
		{
			const auto r = scan(l, ev, [](std::size_t, int, int) {});
			accepted[l] = r.first;
			tried[l] = r.second;
		}
	}
	std::size_t total = 0;
	for (std::size_t l = 0; l < L; l++)
	{
		res.accepted += accepted[l];
		res.tried += tried[l];
	}
	total = res.accepted;
	if (total == 0) return res;
	// Which accepted windows to keep: all, or `wanted` distinct ranks
	// (Floyd's sampling), in increasing order.
	std::vector<std::size_t> chosen;
	if (total <= wanted)
	{
		chosen.resize(total);
		std::iota(chosen.begin(), chosen.end(), std::size_t(0));
	}
	else
	{
		std::set<std::size_t> pick;
		for (std::size_t j = total - wanted; j < total; j++)
		{
			const std::size_t t = rng.below(j + 1);
			if (!pick.insert(t).second) pick.insert(j);
		}
		chosen.assign(pick.begin(), pick.end());
	}
	// Second pass over the levels holding chosen windows.
	std::vector<std::size_t> offset(L + 1, 0);
	for (std::size_t l = 0; l < L; l++) offset[l + 1] = offset[l] + accepted[l];
	std::vector<std::vector<cv::Mat>> found(L);
#pragma omp parallel num_threads(threads)
	{
		CascadeEvaluator ev(cascade);
#pragma omp for schedule(dynamic, 1)
		for (std::size_t l = 0; l < L; l++)
		{
			auto it = std::lower_bound(chosen.begin(), chosen.end(), offset[l]);
			if (it == chosen.end() || *it >= offset[l + 1]) continue;
			scan(
			    l, ev,
			    [&](std::size_t rank, int x, int y)
			    {
				    if (it != chosen.end() && *it == offset[l] + rank)
				    {
					    found[l].push_back(
					        levels[l]
					            .img(cv::Rect(x, y, win.width, win.height))
					            .clone());
					    ++it;
				    }
			    });
		}
	}
	for (auto& f : found)
		for (auto& w : f) res.windows.push_back(std::move(w));
	return res;
}

/** The positives' integral images (posII), the low-contrast ones dropped
 * (the detector never evaluates such windows), and their indices into
 * `positives` (posIndex). */
void usablePositives(
    const std::vector<cv::Mat>& positives, cv::Size win,
    CascadeTrainer::Report& report, std::vector<IntegralImages>& posII,
    std::vector<int>& posIndex)
{
	report.positivesGiven = positives.size();
	for (std::size_t i = 0; i < positives.size(); i++)
	{
		const cv::Mat& p = positives[i];
		if (p.type() != CV_8UC1 || p.size() != win)
			throw CascadeError(
			    "positive " + std::to_string(i) + " is not an 8-bit " +
			    std::to_string(win.width) + "x" + std::to_string(win.height) +
			    " window");
		IntegralImages ii(p, true);
		float nf;
		if (!detail::varianceNormFactor(
		        ii.sum().ptr<int32_t>(), ii.sqsum().ptr<double>(),
		        ii.sum().cols, ii.sqsum().cols, win, nf))
		{
			report.positivesLowContrast++;
			continue;
		}
		posII.push_back(std::move(ii));
		posIndex.push_back(static_cast<int>(i));
	}
}

/** Negative pyramids, as detectMultiScale scales an image (with a range
 * gate: the levels with a window it lets through). */
std::vector<Level> negativePyramids(
    const std::vector<NegativeImage>& negatives, cv::Size win,
    double scaleFactor)
{
	std::vector<Level> levels;
	for (std::size_t i = 0; i < negatives.size(); i++)
	{
		const cv::Mat& img = negatives[i].image;
		if (img.empty()) continue;
		if (img.type() != CV_8UC1)
			throw CascadeError(
			    "negative image " + std::to_string(i) + " is not 8-bit grey");
		const NegativeImage& neg = negatives[i];
		for (double s = 1;; s *= scaleFactor)
		{
			const cv::Size sz(cvRound(img.cols / s), cvRound(img.rows / s));
			if (sz.width < win.width || sz.height < win.height) break;
			if (neg.maxScale > 0 && s > neg.maxScale * (1 + 1e-9)) break;
			if (s < neg.minScale * (1 - 1e-9)) continue;
			Level L;
			L.image = static_cast<int>(i);
			L.scale = s;
			if (sz == img.size())
				L.img = img;
			else
				cv::resize(img, L.img, sz, 0, 0, cv::INTER_LINEAR);
			L.nx = sz.width - win.width + 1;
			L.ny = sz.height - win.height + 1;
			if (!neg.range.empty())
			{
				// The windows the detector's range gate lets through.
				cv::Mat r;
				cv::resize(neg.range, r, sz, 0, 0, cv::INTER_NEAREST);
				const int st = L.step();
				const double side =
				    std::max(cvRound(win.width * s), cvRound(win.height * s));
				bool any = false;
				for (int y = 0; y < L.ny; y += st)
					for (int x = 0; x < L.nx; x += st)
					{
						const bool ok = neg.gate.accepts(
						    RangeGate::windowRange(r, x, y, win), side);
						L.allowed.push_back(ok);
						any |= ok;
					}
				if (!any) continue;
			}
			levels.push_back(std::move(L));
		}
	}
	if (levels.empty())
		throw CascadeError(
		    "no negative image is at least as large as the " +
		    std::to_string(win.width) + "x" + std::to_string(win.height) +
		    " window with a window its range gate lets through");
	return levels;
}

/** The positives the cascade so far still accepts, into `samples`
 * (calibration ones labelled 2). */
void addAcceptedPositives(
    const HaarCascade& cascade, const std::vector<cv::Mat>& positives,
    const std::vector<IntegralImages>& posII, const std::vector<int>& posIndex,
    const std::vector<char>& isCalib, int threads, SampleSet& samples,
    CascadeTrainer::StageReport& rep)
{
	std::vector<char> keep(posII.size(), 0);
#pragma omp parallel num_threads(threads)
	{
		CascadeEvaluator ev(cascade);
#pragma omp for schedule(static)
		for (std::size_t i = 0; i < posII.size(); i++)
		{
			ev.setIntegralImages(posII[i]);
			keep[i] = ev.accepted(ev.evaluate({0, 0}));
		}
	}
	for (std::size_t i = 0; i < posII.size(); i++)
		if (keep[i] && isCalib[i])
		{
			samples.add(positives[posIndex[i]], +2);
			rep.calibrationPositives++;
		}
		else if (keep[i])
		{
			samples.add(positives[posIndex[i]], +1);
			rep.positiveIndices.push_back(posIndex[i]);
		}
	rep.positives = rep.positiveIndices.size();
}

/** One stage boosted on `samples` (features drawn from the pool with
 * feature_fraction). */
HaarCascade::Stage boostStage(
    const SampleSet& samples, const std::vector<HaarFeature>& pool,
    const CascadeTrainer::TOptions& opt, int threads, detail::Random& rng,
    CascadeTrainer::StageReport& rep)
{
	StageTrainer st{samples, pool, {}, opt, threads, {}, {}};
	st.candidates.resize(pool.size());
	std::iota(st.candidates.begin(), st.candidates.end(), 0);
	if (opt.featureFraction < 1.0)
	{
		std::vector<int> sub;
		for (int f : st.candidates)
			if (rng.uniform() < opt.featureFraction) sub.push_back(f);
		if (!sub.empty()) st.candidates = std::move(sub);
	}
	const auto tb = Clock::now();
	st.binFeatures();
	rep.secondsBinning = secondsSince(tb);
	const auto tt = Clock::now();
	std::vector<int> used;
	HaarCascade::Stage stage = st.train(rep, used, rng);
	rep.secondsBoosting = secondsSince(tt);
	return stage;
}

/** Appends `stage` to `cascade`, its stumps' pool indices turned into
 * cascade feature indices (the pool features it did not hold added). */
void appendStage(
    HaarCascade& cascade, HaarCascade::Stage stage,
    const std::vector<HaarFeature>& pool, std::map<int, int>& poolToCascade)
{
	// Pool indices -> cascade feature indices.
	for (auto& stump : stage.stumps)
	{
		auto it = poolToCascade.find(stump.featureIdx);
		if (it == poolToCascade.end())
		{
			it = poolToCascade
			         .emplace(
			             stump.featureIdx,
			             static_cast<int>(cascade.features.size()))
			         .first;
			cascade.features.push_back(pool[stump.featureIdx]);
		}
		stump.featureIdx = it->second;
	}
	cascade.stages.push_back(std::move(stage));
}
}  // namespace

HaarCascade CascadeTrainer::train(
    const std::vector<cv::Mat>& positives,
    const std::vector<NegativeImage>& negatives, uint64_t seed,
    const Progress& progress)
{
	const auto t0 = Clock::now();
	const TOptions& opt = m_options;
	m_report = Report();
	const int threads = opt.threads > 0 ? opt.threads : omp_get_num_procs();
	const cv::Size win(opt.windowWidth, opt.windowHeight);

	// Positives: all must be window-sized 8-bit; low-contrast ones are
	// dropped.
	std::vector<IntegralImages> posII;
	std::vector<int> posIndex;
	usablePositives(positives, win, m_report, posII, posIndex);
	// Calibration positives: a seeded draw of its own (the other draws are
	// those of a training without them).
	std::vector<char> isCalib(posII.size(), 0);
	if (opt.calibrationFraction > 0)
	{
		detail::Random calRng(seed ^ 0x5ca1ab1e0ddba11ULL);
		for (auto& c : isCalib) c = calRng.uniform() < opt.calibrationFraction;
	}
	if (posII.empty())
		throw CascadeError(
		    "no usable positive sample (" + std::to_string(positives.size()) +
		    " given, all with grey-level standard deviation <= 10)");

	const std::vector<Level> levels =
	    negativePyramids(negatives, win, opt.negativeScaleFactor);
	const std::vector<HaarFeature> pool = generateHaarFeatures(win, opt.mode);
	m_report.featurePool = pool.size();
	detail::Random rng(seed);
	const double targetFA = opt.targetFalseAlarm > 0
	                            ? opt.targetFalseAlarm
	                            : std::pow(opt.maxFalseAlarm, opt.numStages);

	// The cascade during training holds only the features it uses.
	HaarCascade cascade;
	cascade.windowSize = win;
	cascade.params.minHitRate = opt.minHitRate;
	cascade.params.maxFalseAlarm = opt.maxFalseAlarm;
	cascade.params.weightTrimRate = opt.weightTrimRate;
	cascade.params.maxWeakCount = opt.maxWeakCount;
	cascade.params.mode = opt.mode;
	std::map<int, int> poolToCascade;

	for (int s = 0; s < opt.numStages; s++)
	{
		const auto ts = Clock::now();
		if (progress)
			progress(
			    std::size_t(s), std::size_t(opt.numStages),
			    "stage " + std::to_string(s + 1) + ": drawing samples");
		StageReport rep;
		SampleSet samples(win);
		addAcceptedPositives(
		    cascade, positives, posII, posIndex, isCalib, threads, samples,
		    rep);
		if (rep.positives == 0)
		{
			m_report.stopReason = "no positive left";
			break;
		}

		const auto tn = Clock::now();
		MiningResult neg = mineNegatives(
		    cascade, levels, negatives, opt.negativeMaxIou,
		    std::size_t(opt.negativesPerStage), rng, threads);
		rep.secondsNegatives = secondsSince(tn);
		rep.acceptanceRatio = neg.acceptanceRatio();
		rep.negativeWindows = neg.tried;
		m_report.finalAcceptanceRatio = rep.acceptanceRatio;
		MRPT_LOG_INFO_FMT(
		    "stage %d: %zu positives, %zu/%zu negative windows accepted "
		    "(ratio %.3g)",
		    s + 1, rep.positives, neg.accepted, neg.tried, rep.acceptanceRatio);
		if (neg.tried > 0 && rep.acceptanceRatio <= targetFA)
		{
			m_report.stopReason = "target false-alarm rate reached";
			break;
		}
		if (neg.windows.size() < std::size_t(opt.minNegatives))
		{
			m_report.stopReason =
			    "negative windows exhausted (the cascade accepts " +
			    std::to_string(neg.windows.size()) + " of " +
			    std::to_string(neg.tried) + " negative windows)";
			break;
		}
		for (const auto& w : neg.windows)
			if (!samples.add(w, -1))
				throw CascadeError("internal: mined a low-contrast window");
		rep.negatives = neg.windows.size();
		samples.finish();

		if (progress)
			progress(
			    std::size_t(s), std::size_t(opt.numStages),
			    "stage " + std::to_string(s + 1) + ": boosting");
		HaarCascade::Stage stage =
		    boostStage(samples, pool, opt, threads, rng, rep);
		appendStage(cascade, std::move(stage), pool, poolToCascade);
		rep.seconds = secondsSince(ts);
		MRPT_LOG_INFO_FMT(
		    "stage %d: %zu stumps, hit rate %.4f, false alarm %.4f, %.1f s",
		    s + 1, rep.weakCount, rep.hitRate, rep.falseAlarm, rep.seconds);
		m_report.stages.push_back(std::move(rep));
		if (progress)
			progress(
			    std::size_t(s + 1), std::size_t(opt.numStages),
			    "stage " + std::to_string(s + 1) + " done");
	}
	if (m_report.stopReason.empty())
		m_report.stopReason = "stage count reached";
	if (cascade.stages.empty())
		throw CascadeError(
		    "training produced no stage: " + m_report.stopReason);
	m_report.seconds = secondsSince(t0);
	return cascade;
}

}  // namespace semnav