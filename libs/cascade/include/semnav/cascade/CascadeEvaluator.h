/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/cascade/HaarCascade.h>
#include <semnav/cascade/IntegralImages.h>

#include <memory>
#include <opencv2/core/mat.hpp>
#include <vector>

namespace semnav
{
namespace detail
{
struct CompiledFeature;
}

/** Runs a HaarCascade on windows of an image exactly as OpenCV 4's
 * cv::CascadeClassifier does at one scale: integral images of the 8-bit
 * image; per window the variance normalisation of HaarEvaluator::setWindow
 * (factor 1/sqrt(area*sqsum - sum^2) over the window shrunk by one pixel;
 * windows whose standard deviation is <= 10 grey levels are skipped);
 * feature values in float times that factor; per stage the sum (double) of
 * the stumps' leaves (value < threshold ? left : right) against the stage
 * threshold minus 1e-5. The trainer uses it to bootstrap negatives; tests
 * compare it with cv::CascadeClassifier window by window.
 *
 * Not thread-safe for setImage(); evaluate() is const and may run
 * concurrently once the image is set. */
class CascadeEvaluator
{
public:
	/** Result of one window. */
	struct Result
	{
		/** -1: skipped by the variance test (or outside the image);
		 * 0..n-1: rejected by that stage; n = stage count: accepted. */
		int stage = -1;
		/** Sum of the last stage evaluated (0 when skipped). */
		double sum = 0;
		bool skipped() const { return stage < 0; }
	};
	/** One window of scanScaleOne(). */
	struct ScannedWindow
	{
		cv::Point origin;
		Result result;
	};

	explicit CascadeEvaluator(HaarCascade cascade);
	~CascadeEvaluator();
	CascadeEvaluator(CascadeEvaluator&&) noexcept;
	CascadeEvaluator& operator=(CascadeEvaluator&&) noexcept;

	const HaarCascade& cascade() const { return m_cascade; }
	std::size_t stageCount() const { return m_cascade.stages.size(); }
	bool accepted(const Result& r) const
	{
		return r.stage == static_cast<int>(stageCount());
	}

	/** Sets a CV_8UC1 image (computes its integral images). */
	void setImage(const cv::Mat& image);
	/** Uses integral images computed elsewhere (e.g. of a training window);
	 * they must outlive the evaluation calls. */
	void setIntegralImages(const IntegralImages& ii);
	const IntegralImages& integralImages() const { return *m_ii; }

	/** Evaluates the window with top-left `origin` (all stages, stopping at
	 * the first rejecting one). */
	Result evaluate(cv::Point origin) const;
	/** Evaluates stages [first, first + count) only (a window that passes
	 * them all gets stage = first + count). */
	Result evaluateStages(
	    cv::Point origin, std::size_t first, std::size_t count) const;

	/** The windows cv::CascadeClassifier::detectMultiScale evaluates at
	 * scale 1 (its first pyramid level), in row-major order: step 2 in x
	 * and y, and the next x position skipped after a rejection by stage 0
	 * (CascadeClassifierInvoker). */
	std::vector<ScannedWindow> scanScaleOne() const;

private:
	void compile();
	HaarCascade m_cascade;
	std::vector<detail::CompiledFeature> m_compiled;
	int m_stride = -1;
	IntegralImages m_own;
	const IntegralImages* m_ii = &m_own;
};

}  // namespace semnav
