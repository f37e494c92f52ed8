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
struct FlatStump;
}  // namespace detail

/** Runs a HaarCascade on windows of an image exactly as OpenCV 4's
 * cv::CascadeClassifier does at one scale: integral images of the 8-bit
 * image; per window the variance normalisation of HaarEvaluator::setWindow
 * (factor 1/sqrt(area*sqsum - sum^2) over the window shrunk by one pixel;
 * windows whose standard deviation is <= 10 grey levels are skipped);
 * feature values in float times that factor; per stage the sum (double) of
 * the stumps' leaves (value < threshold ? left : right) against the stage
 * threshold minus 1e-5. The trainer uses it to bootstrap negatives,
 * CascadeDetector's range-gated search runs scanWindows() on each pyramid
 * level; tests compare it with cv::CascadeClassifier window by window.
 *
 * Not thread-safe for setImage() and scanWindows() (scratch buffers);
 * evaluate() is const and may run concurrently once the image is set. */
class CascadeEvaluator
{
public:
	/** Result of one window. */
	struct Result
	{
		/** -1: skipped by the variance test (or outside the image);
		 * kNotVisited (scanWindows): not evaluated, it follows a window
		 * rejected by stage 0; 0..n-1: rejected by that stage; n = stage
		 * count: accepted. */
		int stage = -1;
		/** Sum of the last stage evaluated (0 when skipped). */
		double sum = 0;
		bool skipped() const { return stage < 0; }
	};
	/** Result::stage of a window scanWindows() does not evaluate. */
	static constexpr int kNotVisited = -2;
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

	/** Evaluates `windows` (top-left corners, in the row-major order
	 * detectMultiScale visits one pyramid level whose window step is
	 * `step`) as detectMultiScale does: a window at (x + step, y) that
	 * directly follows a window at (x, y) rejected by stage 0 is not
	 * evaluated (stage kNotVisited); every other result is evaluate()'s
	 * (same stage and sum, bit for bit). Runs stage by stage over the
	 * windows still in; with AVX2 (setSimd()) eight neighbouring windows
	 * of a row at a time. */
	void scanWindows(
	    const std::vector<cv::Point>& windows, int step,
	    std::vector<Result>& results);
	/** scanWindows() uses AVX2 when the CPU has it (default) or, with
	 * false, the portable loop; both give the same results. */
	void setSimd(bool on) { m_simd = on; }
	/** Whether scanWindows() runs on AVX2 (setSimd and the CPU). */
	bool simdActive() const;

private:
	void compile();
	// scanWindows()'s steps.
	/** Places the windows inside the image on segments of a grid
	 * (m_segments, m_gridOf); returns the number of grid positions. */
	int placeOnGrid(const std::vector<cv::Point>& windows, int step);
	/** Per grid position: its window, variance factor, and alive where the
	 * window has variance. */
	void markVarianceWindows(const std::vector<cv::Point>& windows, int grid);
	/** Stage s's sums of the first nLive live positions (m_gridSums). */
	void runStage(std::size_t s, int step, std::size_t nLive);
	/** Stage 0's results with OpenCV's skip after a rejection; returns how
	 * many positions stay live. */
	std::size_t applyFirstStage(
	    const std::vector<cv::Point>& windows, int step,
	    std::vector<Result>& results, std::size_t nLive);
	HaarCascade m_cascade;
	std::vector<detail::CompiledFeature> m_compiled;
	/** Every stage's stumps with their features compiled, in order;
	 * stage s is [m_stageBegin[s], m_stageBegin[s + 1]). */
	std::vector<detail::FlatStump> m_flat;
	std::vector<std::size_t> m_stageBegin;
	bool m_simd = true;
	/** Largest corner offset of any stump (reads of a window reach this
	 * far past its top-left entry). */
	int m_maxOffset = 0;
	/** scanWindows() scratch: runs of windows of one row on the level's
	 * grid, and per grid position whether it is still in, its variance
	 * factor, its last stage sum and its window (-1: none). */
	struct Segment
	{
		int x0, y, grid, count;
	};
	std::vector<Segment> m_segments;
	struct Live
	{
		int grid, segment;
	};
	std::vector<Live> m_live;
	std::vector<int> m_gridOf;
	std::vector<uint8_t> m_alive;
	std::vector<float> m_gridNf;
	std::vector<double> m_gridSums;
	std::vector<int32_t> m_gridWindow;
	int m_stride = -1;
	IntegralImages m_own;
	const IntegralImages* m_ii = &m_own;
};

}  // namespace semnav
