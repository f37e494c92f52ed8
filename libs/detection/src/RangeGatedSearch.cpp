/* semnav: semantic navigation from tilting-laser sweeps */
#include "RangeGatedSearch.h"

#include <algorithm>
#include <climits>
#include <opencv2/imgproc.hpp>
#include <opencv2/objdetect.hpp>

namespace semnav::detail
{
namespace
{
/** The band's nearest and farthest ranges (rMax 0: none) and each row's
 * first and last column with a range (sc.bandFirst, sc.bandLast). */
void bandExtent(
    const cv::Mat& range, GatedScratch& sc, float& rMin, float& rMax)
{
	rMin = std::numeric_limits<float>::infinity();
	rMax = 0;
	sc.bandFirst.assign(range.rows, range.cols);
	sc.bandLast.assign(range.rows, -1);
	constexpr float kInf = std::numeric_limits<float>::infinity();
	for (int r = 0; r < range.rows; r++)
	{
		// From both ends to the first range, then the extremes between
		// without branches (ranges are >= 0; 0 = none).
		const float* row = range.ptr<float>(r);
		int first = 0, last = range.cols - 1;
		while (first < range.cols && !(row[first] > 0)) first++;
		if (first == range.cols) continue;
		while (!(row[last] > 0)) last--;
		sc.bandFirst[r] = first;
		sc.bandLast[r] = last;
		for (int c = first; c <= last; c++)
		{
			const float v = row[c];
			rMin = std::min(rMin, v > 0 ? v : kInf);
			rMax = std::max(rMax, v);
		}
	}
}

/** cv::resize's nearest neighbour takes level column c from one band
 * column and level row r from one band row, each from its own axis'
 * sizes: resizing the indices gives that map. */
void nearestMap(
    int from, int to, std::vector<int>& map, bool columns, GatedScratch& sc)
{
	sc.mapIn.create(columns ? 1 : from, columns ? from : 1, CV_32S);
	for (int i = 0; i < from; i++) sc.mapIn.at<int32_t>(i) = i;
	cv::resize(
	    sc.mapIn, sc.mapOut, columns ? cv::Size(to, 1) : cv::Size(1, to), 0, 0,
	    cv::INTER_NEAREST);
	map.assign(sc.mapOut.ptr<int32_t>(), sc.mapOut.ptr<int32_t>() + to);
}

/** A level's ranges (sc.levelRows), as cv::resize(INTER_NEAREST) of the
 * band's gives them, in the rows with a range only; per level row its
 * first and last column with a range (sc.first, sc.last). */
void levelRanges(const cv::Mat& range, cv::Size sz, GatedScratch& sc)
{
	nearestMap(range.cols, sz.width, sc.colMap, true, sc);
	nearestMap(range.rows, sz.height, sc.rowMap, false, sc);
	cv::Mat& levelRange = sc.levelRange;
	levelRange.create(sz, CV_32F);
	sc.zeros.assign(sz.width, 0.f);
	sc.levelRows.resize(sz.height);
	sc.first.assign(sz.height, sz.width);
	sc.last.assign(sz.height, -1);
	for (int r = 0; r < sz.height; r++)
	{
		const int br = sc.rowMap[r];
		if (sc.bandFirst[br] > sc.bandLast[br])
		{
			sc.levelRows[r] = sc.zeros.data();
			continue;
		}
		// Columns mapped into the band row's first..last (the map
		// never decreases): outside them the level row is 0.
		const int c0 = static_cast<int>(
		    std::lower_bound(
		        sc.colMap.begin(), sc.colMap.end(), sc.bandFirst[br]) -
		    sc.colMap.begin());
		const int c1 =
		    static_cast<int>(
		        std::upper_bound(
		            sc.colMap.begin(), sc.colMap.end(), sc.bandLast[br]) -
		        sc.colMap.begin()) -
		    1;
		const float* src = range.ptr<float>(br);
		float* dst = levelRange.ptr<float>(r);
		std::fill(dst, dst + sz.width, 0.f);
		for (int c = c0; c <= c1; c++) dst[c] = src[sc.colMap[c]];
		sc.levelRows[r] = dst;
		sc.first[r] = c0;
		sc.last[r] = c1;
	}
}

/** The windows (sc.windows) on the step grid whose range, the nearest of
 * RangeGate::windowRange's five samples, `gb` takes. */
void gatedWindows(
    cv::Size sz, cv::Size win, int step, const GateBounds gb, GatedScratch& sc)
{
	std::vector<cv::Point>& windows = sc.windows;
	// The five samples of RangeGate::windowRange, relative to (x, y); they
	// lie inside the window, so inside the level.
	const int hx = win.width / 2, hy = win.height / 2;
	const int qx = win.width / 4, qy = win.height / 4;
	const int nx = sz.width + 1 - win.width;
	const int ny = sz.height + 1 - win.height;
	windows.clear();
	sc.ok.resize(nx + 1);
	constexpr float kNone = std::numeric_limits<float>::infinity();
	for (int y = 0; y < ny; y += step)
	{
		const int cy = y + hy;
		const int rows[3] = {cy, cy - qy, cy + qy};
		// Columns of the samples with a range: the centre column
		// cx = x + hx, or cx -+ qx in the centre row.
		int lo = INT_MAX, hi = INT_MIN;
		for (int i = 0; i < 3; i++)
		{
			if (sc.first[rows[i]] > sc.last[rows[i]]) continue;
			const int reach = i == 0 ? qx : 0;
			lo = std::min(lo, sc.first[rows[i]] - hx - reach);
			hi = std::max(hi, sc.last[rows[i]] - hx + reach);
		}
		if (lo > hi) continue;
		// On the step grid from 0.
		const int x0 = std::max(0, (lo + step - 1) / step * step);
		const int x1 = std::min(nx - 1, hi);
		if (x0 > x1) continue;
		const float* c = sc.levelRows[cy] + hx;
		const float* a = sc.levelRows[cy - qy] + hx;
		const float* b = sc.levelRows[cy + qy] + hx;
		uint8_t* ok = sc.ok.data();
		// Every column (a plain loop the compiler vectorises), then
		// the grid's. The nearest sample with a range (windowRange;
		// none: infinity, which the gate refuses).
		for (int x = x0; x <= x1; x++)
		{
			const float v0 = c[x], v1 = c[x - qx], v2 = c[x + qx], v3 = a[x],
			            v4 = b[x];
			float r = v0 > 0 ? v0 : kNone;
			r = std::min(r, v1 > 0 ? v1 : kNone);
			r = std::min(r, v2 > 0 ? v2 : kNone);
			r = std::min(r, v3 > 0 ? v3 : kNone);
			r = std::min(r, v4 > 0 ? v4 : kNone);
			const bool nearCut = r < gb.cut;
			ok[x - x0] = (r <= gb.hi) & ((nearCut & (r >= gb.loCut)) |
			                             (!nearCut & (r >= gb.lo)));
		}
		for (int x = x0; x <= x1; x += step)
			if (ok[x - x0]) windows.emplace_back(x, y);
	}
}

/** Evaluates the windows (sc.windows) of the level of size sz, cluster by
 * cluster; sc.accepted per window. */
void evaluateWindows(
    CascadeEvaluator& ev, const cv::Mat& image, cv::Size sz, cv::Size win,
    int step, GatedScratch& sc)
{
	const std::vector<cv::Point>& windows = sc.windows;
	// Clusters of windows apart from each other (bands of window rows
	// less than a window height apart, then in a band the columns of
	// overlapping windows): each cluster's part of the level
	// (cv::resize, INTER_LINEAR_EXACT) and integral images cover its
	// windows only, as a window reads within itself. Neighbours on a
	// row (OpenCV's skip after a stage-0 rejection) share a cluster.
	sc.accepted.assign(windows.size(), 0);
	for (std::size_t i0 = 0, i1; i0 < windows.size(); i0 = i1)
	{
		for (i1 = i0 + 1; i1 < windows.size() &&
		                  windows[i1].y - windows[i1 - 1].y < win.height;
		     i1++)
			;
		// The band's columns covered by windows (a difference array),
		// in runs.
		sc.cover.assign(std::size_t(sz.width + 1), 0);
		for (std::size_t i = i0; i < i1; i++)
		{
			sc.cover[std::size_t(windows[i].x)]++;
			sc.cover[std::size_t(windows[i].x + win.width)]--;
		}
		sc.spans.clear();
		sc.spanOf.resize(std::size_t(sz.width));
		for (int x = 0, n = 0; x < sz.width; x++)
		{
			const int before = n;
			n += sc.cover[std::size_t(x)];
			if (n > 0 && before == 0)
				sc.spans.emplace_back(x, x + 1);
			else if (n > 0)
				sc.spans.back().second = x + 1;
			sc.spanOf[std::size_t(x)] = int(sc.spans.size()) - 1;
		}
		// The band's windows by span (a stable counting sort: each
		// span's in row-major order).
		const std::size_t nSpans = sc.spans.size();
		sc.spanStart.assign(nSpans + 1, 0);
		for (std::size_t i = i0; i < i1; i++)
			sc.spanStart
			    [std::size_t(sc.spanOf[std::size_t(windows[i].x)]) + 1]++;
		for (std::size_t k = 0; k < nSpans; k++)
			sc.spanStart[k + 1] += sc.spanStart[k];
		sc.partIndex.resize(i1 - i0);
		sc.fill.assign(sc.spanStart.begin(), sc.spanStart.end() - 1);
		for (std::size_t i = i0; i < i1; i++)
			sc.partIndex[sc.fill[std::size_t(
			    sc.spanOf[std::size_t(windows[i].x)])]++] = i;
		for (std::size_t k = 0; k < nSpans; k++)
		{
			const std::size_t* idx = sc.partIndex.data() + sc.spanStart[k];
			const std::size_t count = sc.spanStart[k + 1] - sc.spanStart[k];
			// The span's columns, its first and last window's rows.
			const cv::Rect box(
			    sc.spans[k].first, windows[idx[0]].y,
			    sc.spans[k].second - sc.spans[k].first,
			    windows[idx[count - 1]].y + win.height - windows[idx[0]].y);
			sc.part.resize(count);
			for (std::size_t j = 0; j < count; j++)
				sc.part[j] = windows[idx[j]] - box.tl();
			cv::Mat part = image(box);
			if (sz != image.size())
			{
				sc.resize.resize(image, sz, box, sc.levelPart);
				part = sc.levelPart;
			}
			sc.ii.compute(part, ev.cascade().hasTiltedFeatures(), sc.stride);
			ev.setIntegralImages(sc.ii);
			ev.scanWindows(sc.part, step, sc.results);
			for (std::size_t j = 0; j < count; j++)
				sc.accepted[idx[j]] = ev.accepted(sc.results[j]);
		}
	}
}
}  // namespace

void rangeGatedDetect(
    CascadeEvaluator& ev, const cv::Mat& image, const cv::Mat& range,
    double scaleFactor, int minNeighbors, int windowStep, cv::Size minSize,
    cv::Size maxSize, const RangeGate& gate, std::vector<cv::Rect>& found,
    std::vector<int>& weights, GatedScratch& sc)
{
	found.clear();
	weights.clear();
	const cv::Size win = ev.cascade().windowSize;
	if (maxSize.area() == 0) maxSize = image.size();
	sc.stride = std::max(sc.stride, image.cols + 1);
	// The band's nearest and farthest ranges (a level none of whose
	// window sides takes them is skipped whole: its nearest-neighbour
	// ranges are some of the band's).
	float rMin = 0, rMax = 0;
	bandExtent(range, sc, rMin, rMax);
	for (double factor = 1;; factor *= scaleFactor)
	{
		const cv::Size ws(
		    cvRound(win.width * factor), cvRound(win.height * factor));
		const cv::Size sz(
		    cvRound(image.cols / factor), cvRound(image.rows / factor));
		if (sz.width <= win.width || sz.height <= win.height) break;
		if (ws.width > maxSize.width || ws.height > maxSize.height) break;
		if (ws.width < minSize.width || ws.height < minSize.height) continue;
		const double side = std::max(ws.width, ws.height);
		const GateBounds gb(gate, side);
		if (rMax == 0 || rMin > gb.hi || rMax < std::min(gb.lo, gb.loCut))
			continue;
		// The level's ranges, as cv::resize(INTER_NEAREST) gives them, in
		// the rows with a range only.
		levelRanges(range, sz, sc);
		const int step = windowStep > 0 ? windowStep : factor > 2 ? 1 : 2;
		gatedWindows(sz, win, step, gb, sc);
		if (sc.windows.empty()) continue;
		evaluateWindows(ev, image, sz, win, step, sc);
		for (std::size_t j = 0; j < sc.windows.size(); j++)
			if (sc.accepted[j])
				found.emplace_back(
				    cvRound(sc.windows[j].x * factor),
				    cvRound(sc.windows[j].y * factor), ws.width, ws.height);
	}
	cv::groupRectangles(found, weights, minNeighbors, 0.2);
}

}  // namespace semnav::detail
