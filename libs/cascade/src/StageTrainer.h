/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once
/* CascadeTrainer's boosting of one stage: the training windows
 * (SampleSet) and Gentle AdaBoost on regression stumps (StageTrainer).
 * Internal to the cascade library. */

#include <semnav/cascade/CascadeTrainer.h>
#include <semnav/cascade/HaarCascade.h>
#include <semnav/cascade/HaarFeature.h>
#include <semnav/cascade/IntegralImages.h>

#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "CompiledFeature.h"
#include "Random.h"

namespace semnav::detail
{
/** Training windows with their integral images (window size + 1 square)
 * and variance normalisation factors. After finish(), the integral images
 * are stored transposed (entry-major: one row of all samples per integral
 * image entry), so that a feature's values over all samples stream through
 * a dozen contiguous rows. */
class SampleSet
{
public:
	explicit SampleSet(cv::Size win)
	    : m_win(win),
	      m_stride(win.width + 1),
	      m_area((win.width + 1) * (win.height + 1))
	{
	}
	/** Adds a window; false (not added) when OpenCV would skip it. */
	bool add(const cv::Mat& window, int label)
	{
		m_ii.compute(window, true);
		float nf = 1;
		if (!varianceNormFactor(
		        m_ii.sum().ptr<int32_t>(), m_ii.sqsum().ptr<double>(), m_stride,
		        m_stride, m_win, nf))
			return false;
		m_sum.insert(
		    m_sum.end(), m_ii.sum().ptr<int32_t>(),
		    m_ii.sum().ptr<int32_t>() + m_area);
		m_tilt.insert(
		    m_tilt.end(), m_ii.tilted().ptr<int32_t>(),
		    m_ii.tilted().ptr<int32_t>() + m_area);
		m_nf.push_back(nf);
		m_label.push_back(static_cast<int8_t>(label));
		return true;
	}
	/** Transposes the integral images; call once after the last add(). */
	void finish()
	{
		const std::size_t N = size();
		m_sumT.resize(std::size_t(m_area) * N);
		m_tiltT.resize(std::size_t(m_area) * N);
		for (std::size_t i = 0; i < N; i++)
			for (int p = 0; p < m_area; p++)
			{
				m_sumT[std::size_t(p) * N + i] = m_sum[i * m_area + p];
				m_tiltT[std::size_t(p) * N + i] = m_tilt[i * m_area + p];
			}
		m_sum.clear();
		m_sum.shrink_to_fit();
		m_tilt.clear();
		m_tilt.shrink_to_fit();
	}
	std::size_t size() const { return m_nf.size(); }
	int stride() const { return m_stride; }
	int label(std::size_t i) const { return m_label[i]; }
	/** Normalised values of a feature (compiled with stride()) for all
	 * samples, computed as the detector computes them: float(w0 * s0) +
	 * float(w1 * s1) [+ w2 * s2], times the normalisation factor. */
	void values(const CompiledFeature& f, float* out) const
	{
		const std::size_t N = size();
		const std::vector<int32_t>& T = f.tilted ? m_tiltT : m_sumT;
		const auto row = [&](int ofs) { return &T[std::size_t(ofs) * N]; };
		for (int j = 0; j < 3; j++)
		{
			if (j == 2 && f.weight[2] == 0.0f) break;
			const int32_t *a = row(f.ofs[j][0]), *b = row(f.ofs[j][1]),
			              *c = row(f.ofs[j][2]), *d = row(f.ofs[j][3]);
			const float w = f.weight[j];
			if (j == 0)
				for (std::size_t i = 0; i < N; i++)
					out[i] = w * static_cast<float>(a[i] - b[i] - c[i] + d[i]);
			else
				for (std::size_t i = 0; i < N; i++)
					out[i] += w * static_cast<float>(a[i] - b[i] - c[i] + d[i]);
		}
		for (std::size_t i = 0; i < N; i++) out[i] *= m_nf[i];
	}

private:
	cv::Size m_win;
	int m_stride, m_area;
	IntegralImages m_ii;
	std::vector<int32_t> m_sum, m_tilt, m_sumT, m_tiltT;
	std::vector<float> m_nf;
	std::vector<int8_t> m_label;
};

/** Gentle AdaBoost on regression stumps for one stage. */
struct StageTrainer
{
	const SampleSet& samples;
	const std::vector<HaarFeature>& pool;
	std::vector<int> candidates;  // pool indices usable in this stage
	const CascadeTrainer::TOptions& opt;
	int threads;

	std::vector<uint8_t> codes;  // candidates x samples
	std::vector<CompiledFeature> compiled;

	/** Codes of every candidate's values over the samples (equal-frequency
	 * bins, opt.featureBins). */
	void binFeatures();
	/** Threshold of split "code <= k": the smallest value with a larger
	 * code. */
	float thresholdOf(std::size_t f, int k) const;
	/** Boosts one stage; the pool indices of its stumps' features into
	 * usedPoolIdx. */
	HaarCascade::Stage train(
	    CascadeTrainer::StageReport& rep, std::vector<int>& usedPoolIdx,
	    Random& rng);

private:
	/** Weight trimming: the samples (calibration ones never) outside the
	 * lightest holding (1 - weight_trim_rate) of the mass. */
	void trimWeights(
	    const std::vector<double>& w, const std::vector<char>& calib,
	    std::vector<uint32_t>& active) const;
	/** Per tried candidate f, its best split (bestSplit[f], -1: none) and
	 * its score. */
	void scoreSplits(
	    const std::vector<uint32_t>& tryF, const std::vector<uint32_t>& active,
	    const std::vector<double>& w, const std::vector<double>& wy,
	    std::vector<double>& bestScore, std::vector<int>& bestSplit) const;
	/** The stage threshold keeping min_hit_rate of the P boosted positives
	 * (and of the C calibration ones). */
	float stageThreshold(
	    const std::vector<double>& sums, const std::vector<int>& y,
	    const std::vector<char>& calib, std::size_t P, std::size_t C,
	    std::vector<double>& posSums) const;
};

}  // namespace semnav::detail
