/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once
/* CascadeDetector's range-gated cascade search (range_scales): OpenCV's
 * detectMultiScale search, evaluating only the windows whose range suits
 * their size. Internal to the detection library. */

#include <semnav/cascade/CascadeEvaluator.h>
#include <semnav/cascade/ExactResize.h>
#include <semnav/cascade/IntegralImages.h>
#include <semnav/cascade/RangeGate.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <opencv2/core/mat.hpp>
#include <utility>
#include <vector>

namespace semnav::detail
{
/** Scratch of the range-gated search, kept between calls (no allocation
 * per level or per sweep once grown). */
struct GatedScratch
{
	/** A level's ranges (nearest neighbour of the band's), built only in
	 * the rows whose band row has a range; the others point at zeros. */
	cv::Mat levelRange;
	std::vector<const float*> levelRows;
	std::vector<float> zeros;
	/** The band's first and last column with a range per row, and the
	 * band column and row of each level column and row (cv::resize's
	 * nearest neighbour). */
	std::vector<int> bandFirst, bandLast, colMap, rowMap;
	cv::Mat mapIn, mapOut;
	std::vector<cv::Point> windows;
	std::vector<CascadeEvaluator::Result> results;
	/** Per level row: first and last column with a range (first > last:
	 * none). */
	std::vector<int> first, last;
	/** Per column of a row of windows: whether the gate takes it. */
	std::vector<uint8_t> ok;
	/** A level's windows in clusters: the column spans of a band, a
	 * cluster's windows and their indices, and which were accepted. */
	std::vector<std::pair<int, int>> spans;
	std::vector<int> cover, spanOf;
	std::vector<std::size_t> spanStart, fill;
	std::vector<cv::Point> part;
	std::vector<std::size_t> partIndex;
	std::vector<uint8_t> accepted;
	/** The part of a pyramid level its windows cover. */
	ExactResize resize;
	cv::Mat levelPart;
	IntegralImages ii;
	/** Row stride of the integral images: only grows, so that the
	 * evaluators compile their features once. */
	int stride = 0;
};

/** The float ranges RangeGate::accepts(r, side) takes, as bounds on r:
 * r > 0, r <= hi and r >= (r < cut ? loCut : lo). The gate's size
 * r x side / perSide (double) never decreases with r, so each bound is
 * the first or last float of a run, found by bisection over the float bit
 * patterns: the same decisions as accepts(), bit for bit. */
struct GateBounds
{
	float lo = 0, loCut = 0, hi = 0, cut = 0;

	GateBounds(const RangeGate& g, double side)
	{
		const auto size = [&](float r) { return r * side / g.perSide; };
		hi = lastFloat([&](float r) { return size(r) <= g.hi; });
		lo = firstFloat([&](float r) { return size(r) >= g.lo; });
		loCut = firstFloat([&](float r) { return size(r) >= g.loCut; });
		// r < cutRange (double) <=> r < cutRange rounded up to a float.
		cut = static_cast<float>(g.cutRange);
		if (static_cast<double>(cut) < g.cutRange)
			cut = std::nextafter(cut, std::numeric_limits<float>::infinity());
	}
	bool accepts(float r) const
	{
		return r > 0 && r <= hi && (r < cut ? r >= loCut : r >= lo);
	}
	/** The smallest positive finite float with pred true (pred false then
	 * true as r grows); infinity when none. */
	template <class P>
	static float firstFloat(P pred)
	{
		uint32_t a = 1, b = 0x7f800000u;  // pred(b) taken as true
		while (a < b)
		{
			const uint32_t m = a + (b - a) / 2;
			if (pred(fromBits(m)))
				b = m;
			else
				a = m + 1;
		}
		return fromBits(a);
	}
	/** The largest positive finite float with pred true (true then false);
	 * 0 when none. */
	template <class P>
	static float lastFloat(P pred)
	{
		uint32_t a = 0, b = 0x7f7fffffu;  // pred(a) taken as true
		while (a < b)
		{
			const uint32_t m = a + (b - a + 1) / 2;
			if (pred(fromBits(m)))
				a = m;
			else
				b = m - 1;
		}
		return fromBits(a);
	}
	static float fromBits(uint32_t u)
	{
		float f;
		std::memcpy(&f, &u, sizeof(f));
		return f;
	}
};

/** detectMultiScale's search (its pyramid levels, window steps unless
 * `windowStep` > 0 sets them, skip after a stage-0 rejection and grouping)
 * by CascadeEvaluator, but a window is
 * evaluated only where the range at its centre (the nearest of five
 * samples in its central half; `range` 0 = none) passes `gate` for its
 * side. A level is resized (ExactResize) and its integral images computed
 * only over the windows searched;
 * windows none of whose five samples can have a range (rows and columns
 * without one) are not looked at. */
void rangeGatedDetect(
    CascadeEvaluator& ev, const cv::Mat& image, const cv::Mat& range,
    double scaleFactor, int minNeighbors, int windowStep, cv::Size minSize,
    cv::Size maxSize, const RangeGate& gate, std::vector<cv::Rect>& found,
    std::vector<int>& weights, GatedScratch& sc);

}  // namespace semnav::detail
