/* semnav: semantic navigation from tilting-laser sweeps */
#include "StageTrainer.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace semnav::detail
{
namespace
{
/** Whether a stage sum passes threshold th (as the detector decides). */
bool passes(double s, float th)
{
	return !(s < th - kStageThresholdEps);
}
}  // namespace

void StageTrainer::binFeatures()
{
	const std::size_t N = samples.size(), F = candidates.size();
	codes.assign(F * N, 0);
	compiled.resize(F);
	const int bins = opt.featureBins;
	// Equal-frequency bins from a fine uniform histogram of the values:
	// the code is a monotone (non-decreasing) function of the value, so
	// every sample with code <= k has a smaller value than every sample
	// with a larger code, and equal values share a code. The split
	// threshold is then the smallest value above (thresholdOf()).
	constexpr int kFine = 4096;
#pragma omp parallel num_threads(threads)
	{
		std::vector<float> v(N);
		std::vector<int> fine(N);
		std::vector<uint32_t> hist(kFine);
		std::vector<uint8_t> map(kFine);
#pragma omp for schedule(dynamic, 256)
		for (std::size_t f = 0; f < F; f++)
		{
			compiled[f] =
			    CompiledFeature(pool[candidates[f]], samples.stride());
			samples.values(compiled[f], v.data());
			float mn = v[0], mx = v[0];
			for (std::size_t i = 1; i < N; i++)
			{
				mn = std::min(mn, v[i]);
				mx = std::max(mx, v[i]);
			}
			uint8_t* c = &codes[f * N];
			if (!(mx > mn)) continue;  // constant: one bin
			const float inv = float(kFine) / (mx - mn);
			std::fill(hist.begin(), hist.end(), 0u);
			for (std::size_t i = 0; i < N; i++)
			{
				const int b =
				    std::min(kFine - 1, static_cast<int>((v[i] - mn) * inv));
				fine[i] = b;
				hist[std::size_t(b)]++;
			}
			std::size_t before = 0;
			for (int b = 0; b < kFine; b++)
			{
				map[std::size_t(b)] =
				    static_cast<uint8_t>(std::min<std::size_t>(
				        std::size_t(bins) - 1, before * std::size_t(bins) / N));
				before += hist[std::size_t(b)];
			}
			for (std::size_t i = 0; i < N; i++)
				c[i] = map[std::size_t(fine[i])];
		}
	}
}

float StageTrainer::thresholdOf(std::size_t f, int k) const
{
	const std::size_t N = samples.size();
	std::vector<float> v(N);
	samples.values(compiled[f], v.data());
	float t = std::numeric_limits<float>::infinity();
	for (std::size_t i = 0; i < N; i++)
		if (codes[f * N + i] > k) t = std::min(t, v[i]);
	return t;
}

HaarCascade::Stage StageTrainer::train(
    CascadeTrainer::StageReport& rep, std::vector<int>& usedPoolIdx,
    Random& rng)
{
	const std::size_t N = samples.size(), F = candidates.size();
	std::vector<double> w(N, 1.0 / double(N)), sums(N, 0.0);
	std::vector<int> y(N);
	// Calibration positives (label 2) have no weight: the stumps do not
	// fit them, they only set the stage threshold.
	std::vector<char> calib(N, 0);
	std::size_t P = 0, C = 0;
	for (std::size_t i = 0; i < N; i++)
	{
		y[i] = samples.label(i) > 0 ? 1 : -1;
		calib[i] = samples.label(i) == 2;
		if (calib[i])
			C++;
		else if (y[i] > 0)
			P++;
	}
	if (C > 0)
	{
		const double wb = 1.0 / double(N - C);
		for (std::size_t i = 0; i < N; i++) w[i] = calib[i] ? 0.0 : wb;
	}
	const std::size_t Nn = N - P - C;
	HaarCascade::Stage stage;
	std::vector<double> bestScore(F);
	std::vector<int> bestSplit(F);
	std::vector<uint32_t> active;
	std::vector<double> posSums;
	for (int t = 0; t < opt.maxWeakCount; t++)
	{
		trimWeights(w, calib, active);
		std::vector<double> wy(N);
		for (std::size_t i = 0; i < N; i++) wy[i] = w[i] * y[i];

		// Features tried for this stump (seeded draw).
		std::fill(bestSplit.begin(), bestSplit.end(), -1);
		std::vector<uint32_t> tryF;
		tryF.reserve(F);
		for (std::size_t f = 0; f < F; f++)
			if (opt.roundFeatureFraction >= 1.0 ||
			    rng.uniform() < opt.roundFeatureFraction)
				tryF.push_back(uint32_t(f));
		scoreSplits(tryF, active, w, wy, bestScore, bestSplit);
		std::size_t fb = F;
		for (std::size_t f = 0; f < F; f++)
			if (bestSplit[f] >= 0 && (fb == F || bestScore[f] > bestScore[fb]))
				fb = f;
		if (fb == F) break;  // nothing separates the samples
		const int k = bestSplit[fb];
		const uint8_t* c = &codes[fb * N];
		double wl = 0, sl = 0, wr = 0, sr = 0;
		for (uint32_t i : active)
		{
			if (c[i] <= k)
			{
				wl += w[i];
				sl += wy[i];
			}
			else
			{
				wr += w[i];
				sr += wy[i];
			}
		}
		HaarCascade::Stump st;
		st.featureIdx = candidates[fb];  // pool index for now
		st.threshold = thresholdOf(fb, k);
		st.left = static_cast<float>(wl > 0 ? sl / wl : 0.0);
		st.right = static_cast<float>(wr > 0 ? sr / wr : 0.0);
		stage.stumps.push_back(st);
		usedPoolIdx.push_back(candidates[fb]);

		// Update sums (as the detector: double += float leaf) and
		// weights: w *= exp(-y f(x)).
		double total = 0;
		for (std::size_t i = 0; i < N; i++)
		{
			const float leaf = c[i] <= k ? st.left : st.right;
			sums[i] += leaf;
			w[i] *= std::exp(-double(y[i]) * double(leaf));
			total += w[i];
		}
		for (auto& wi : w) wi /= total;

		// Stage threshold keeping minHitRate of the positives
		// (opencv_traincascade's CvCascadeBoost::isErrDesired).
		const float thr = stageThreshold(sums, y, calib, P, C, posSums);
		const auto hits = [&](float th)
		{
			std::size_t h = 0;
			for (std::size_t i = 0; i < N; i++)
				h += y[i] > 0 && !calib[i] && passes(sums[i], th);
			return h;
		};
		std::size_t fa = 0;
		for (std::size_t i = 0; i < N; i++)
			if (y[i] < 0 && passes(sums[i], thr)) fa++;
		if (C > 0)
		{
			std::size_t hc = 0;
			for (std::size_t i = 0; i < N; i++)
				hc += calib[i] && passes(sums[i], thr);
			rep.calibrationHitRate = double(hc) / double(C);
		}
		stage.threshold = thr;
		rep.hitRate = double(hits(thr)) / double(P);
		rep.falseAlarm = Nn ? double(fa) / double(Nn) : 0.0;
		rep.weakCount = stage.stumps.size();
		rep.threshold = thr;
		if (rep.falseAlarm <= opt.maxFalseAlarm) break;
	}
	return stage;
}

void StageTrainer::trimWeights(
    const std::vector<double>& w, const std::vector<char>& calib,
    std::vector<uint32_t>& active) const
{
	const std::size_t N = w.size();
	active.clear();
	std::vector<double> sorted(w);
	std::sort(sorted.begin(), sorted.end());
	const double total = std::accumulate(sorted.begin(), sorted.end(), 0.0);
	double acc = 0, thr = 0;
	for (double s : sorted)
	{
		acc += s;
		if (acc > (1.0 - opt.weightTrimRate) * total)
		{
			thr = s;
			break;
		}
	}
	for (std::size_t i = 0; i < N; i++)
		if (w[i] >= thr && !calib[i]) active.push_back(uint32_t(i));
}

void StageTrainer::scoreSplits(
    const std::vector<uint32_t>& tryF, const std::vector<uint32_t>& active,
    const std::vector<double>& w, const std::vector<double>& wy,
    std::vector<double>& bestScore, std::vector<int>& bestSplit) const
{
	const std::size_t N = samples.size(), T = tryF.size();
#pragma omp parallel num_threads(threads)
	{
		std::vector<double> hw(256), hs(256);
#pragma omp for schedule(dynamic, 256)
		for (std::size_t t2 = 0; t2 < T; t2++)
		{
			const std::size_t f = tryF[t2];
			std::fill(hw.begin(), hw.end(), 0.0);
			std::fill(hs.begin(), hs.end(), 0.0);
			const uint8_t* c = &codes[f * N];
			int maxCode = 0;
			for (uint32_t i : active)
			{
				const int b = c[i];
				hw[b] += w[i];
				hs[b] += wy[i];
				maxCode = std::max(maxCode, b);
			}
			double W = 0, S = 0;
			for (int b = 0; b <= maxCode; b++)
			{
				W += hw[b];
				S += hs[b];
			}
			double wl = 0, sl = 0, best = -1;
			int split = -1;
			for (int k = 0; k < maxCode; k++)
			{
				wl += hw[k];
				sl += hs[k];
				const double wr = W - wl, sr = S - sl;
				if (wl <= 0 || wr <= 0) continue;
				const double score = sl * sl / wl + sr * sr / wr;
				if (score > best)
				{
					best = score;
					split = k;
				}
			}
			bestScore[f] = best;
			bestSplit[f] = split;
		}
	}
}

float StageTrainer::stageThreshold(
    const std::vector<double>& sums, const std::vector<int>& y,
    const std::vector<char>& calib, std::size_t P, std::size_t C,
    std::vector<double>& posSums) const
{
	const std::size_t N = sums.size();
	// The threshold keeping minHitRate of the positives (boosted or
	// calibration ones), as a float that keeps them all.
	const auto keeping = [&](bool ofCalib, std::size_t count)
	{
		posSums.clear();
		for (std::size_t i = 0; i < N; i++)
			if (y[i] > 0 && bool(calib[i]) == ofCalib)
				posSums.push_back(sums[i]);
		std::sort(posSums.begin(), posSums.end());
		const std::size_t idx = std::min(
		    count - 1, std::size_t((1.0 - opt.minHitRate) * double(count)));
		float th = static_cast<float>(posSums[idx]);
		const auto hits = [&](float t)
		{
			std::size_t h = 0;
			for (double v : posSums) h += passes(v, t);
			return h;
		};
		// Rounding to float must not lose positives the rank
		// promised.
		while (hits(th) < count - idx)
			th = std::nextafter(th, -std::numeric_limits<float>::infinity());
		return th;
	};
	return C > 0 ? std::min(keeping(false, P), keeping(true, C))
	             : keeping(false, P);
}

}  // namespace semnav::detail
