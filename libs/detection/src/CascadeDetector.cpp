/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/config/CConfigFile.h>
#include <mrpt/config/CConfigFileBase.h>
#include <semnav/cascade/CascadeError.h>
#include <semnav/cascade/CascadeEvaluator.h>
#include <semnav/cascade/CascadeXml.h>
#include <semnav/cascade/ExactResize.h>
#include <semnav/cascade/IntegralImages.h>
#include <semnav/cascade/RangeGate.h>
#include <semnav/common/ConfigChecks.h>
#include <semnav/common/Error.h>
#include <semnav/common/ParallelFor.h>
#include <semnav/common/Percentile.h>
#include <semnav/common/Timing.h>
#include <semnav/detection/BackWall.h>
#include <semnav/detection/CascadeDetector.h>
#include <semnav/detection/ObjectScorer.h>
#include <semnav/detection/ShapeVerifier.h>

#include <algorithm>
#include <chrono>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <opencv2/imgproc.hpp>
#include <opencv2/objdetect.hpp>
#include <sstream>
#include <tuple>

namespace semnav
{
namespace
{
using Clock = std::chrono::steady_clock;
}  // namespace

// ------------------------------------------------------------ detector
namespace
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

/** A class's detection passes (TClassOptions::passes: near, far). */
constexpr int kMaxPasses = 2;

/** Index of a class's pass in the per-pass scratch. */
std::size_t slot(std::size_t classIndex, std::size_t pass)
{
	return classIndex * kMaxPasses + pass;
}

}  // namespace

struct CascadeDetector::Impl
{
	std::vector<cv::CascadeClassifier> classifiers;
	/** The same cascades for the range-gated search (range_scales), per
	 * class and pass (slot()). */
	std::vector<CascadeEvaluator> evaluators;
	std::vector<cv::Size> windows;
	/** Per class and pass (slot()): its scaled detection images by
	 * upscale, kept within one detectCandidates() call (passes may run on
	 * their own threads). */
	std::vector<
	    std::map<std::tuple<DetectionChannel, double, int, int, int>, cv::Mat>>
	    scaled;
	bool keepScaled = false;
	PanoramicProjection projection;
	/** DetectionImage::viewRotation() of the last grid. */
	cv::Mat rotation;
	std::vector<double> rotationPhis, rotationThetas;
	/** Per class. */
	std::vector<std::vector<ObjectProposal>> proposals;
	/** Elevations of the first and last row of the detection image. */
	double el0 = -M_PI / 2, el1 = M_PI / 2;
	/** Per class and pass (slot()). */
	std::vector<GatedScratch> gated;
	/** Per class (empty: no shape check). */
	std::vector<ShapeVerifier> verifiers;
	bool describeShapes = false;
};

CascadeDetector::CascadeDetector(const TOptions& options)
    : m_options(options), m_impl(std::make_unique<Impl>())
{
	for (const auto& k : m_options.classes)
	{
		const std::string path = m_options.cascadePath(k);
		// Our reader gives clear errors; OpenCV then loads the same file.
		const HaarCascade full = CascadeXml::readFile(path);
		const bool truncated =
		    k.maxStages > 0 && std::size_t(k.maxStages) < full.stages.size();
		const HaarCascade c =
		    truncated ? full.firstStages(std::size_t(k.maxStages)) : full;
		cv::CascadeClassifier cc;
		if (!truncated && !cc.load(path))
			throw CascadeError("cv::CascadeClassifier cannot load " + path);
		if (truncated)
		{
			// OpenCV reads the same first stages from memory.
			cv::FileStorage fs(
			    CascadeXml::toString(c),
			    cv::FileStorage::READ | cv::FileStorage::MEMORY);
			if (!cc.read(fs.getFirstTopLevelNode()))
				throw CascadeError(
				    "cv::CascadeClassifier cannot read the first " +
				    std::to_string(k.maxStages) + " stages of " + path);
		}
		m_impl->classifiers.push_back(std::move(cc));
		m_impl->windows.push_back(c.windowSize);
		// One per pass: a class's passes may run on their own threads.
		for (int pass = 0; pass < kMaxPasses; pass++)
			m_impl->evaluators.emplace_back(c);
		m_impl->verifiers.push_back(
		    k.shapeModel.empty()
		        ? ShapeVerifier()
		        : ShapeVerifier::load(m_options.resolvePath(k.shapeModel)));
	}
	m_impl->scaled.resize(m_options.classes.size() * kMaxPasses);
	m_impl->gated.resize(m_options.classes.size() * kMaxPasses);
}

void CascadeDetector::describeShapes(bool on)
{
	m_impl->describeShapes = on;
}

CascadeDetector::~CascadeDetector() = default;

void CascadeDetector::setSimd(bool on)
{
	for (auto& ev : m_impl->evaluators) ev.setSimd(on);
}

namespace
{
/** detectMultiScale runs in parallel: its output order varies. A fixed
 * order keeps everything after it deterministic. */
std::vector<std::size_t> fixedOrder(
    const std::vector<cv::Rect>& found, const std::vector<int>& n)
{
	std::vector<std::size_t> order(found.size());
	for (std::size_t j = 0; j < order.size(); j++) order[j] = j;
	std::sort(
	    order.begin(), order.end(),
	    [&](std::size_t a, std::size_t b)
	    {
		    const cv::Rect &ra = found[a], &rb = found[b];
		    return std::tie(ra.y, ra.x, ra.height, ra.width, n[a]) <
		           std::tie(rb.y, rb.x, rb.height, rb.width, n[b]);
	    });
	return order;
}

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
    std::vector<int>& weights, GatedScratch& sc)
{
	found.clear();
	weights.clear();
	const cv::Size win = ev.cascade().windowSize;
	if (maxSize.area() == 0) maxSize = image.size();
	sc.stride = std::max(sc.stride, image.cols + 1);
	cv::Mat& levelRange = sc.levelRange;
	std::vector<cv::Point>& windows = sc.windows;
	// The five samples of RangeGate::windowRange, relative to (x, y); they
	// lie inside the window, so inside the level.
	const int hx = win.width / 2, hy = win.height / 2;
	const int qx = win.width / 4, qy = win.height / 4;
	// The band's nearest and farthest ranges (a level none of whose
	// window sides takes them is skipped whole: its nearest-neighbour
	// ranges are some of the band's) and each row's first and last column
	// with a range.
	float rMin = std::numeric_limits<float>::infinity(), rMax = 0;
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
	// cv::resize's nearest neighbour takes level column c from one band
	// column and level row r from one band row, each from its own axis'
	// sizes: resizing the indices gives that map.
	const auto nearestMap =
	    [&](int from, int to, std::vector<int>& map, bool columns)
	{
		sc.mapIn.create(columns ? 1 : from, columns ? from : 1, CV_32S);
		for (int i = 0; i < from; i++) sc.mapIn.at<int32_t>(i) = i;
		cv::resize(
		    sc.mapIn, sc.mapOut, columns ? cv::Size(to, 1) : cv::Size(1, to), 0,
		    0, cv::INTER_NEAREST);
		map.assign(sc.mapOut.ptr<int32_t>(), sc.mapOut.ptr<int32_t>() + to);
	};
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
		nearestMap(range.cols, sz.width, sc.colMap, true);
		nearestMap(range.rows, sz.height, sc.rowMap, false);
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
		const int nx = sz.width + 1 - win.width;
		const int ny = sz.height + 1 - win.height;
		const int step = windowStep > 0 ? windowStep : factor > 2 ? 1 : 2;
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
				const float v0 = c[x], v1 = c[x - qx], v2 = c[x + qx],
				            v3 = a[x], v4 = b[x];
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
		if (windows.empty()) continue;
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
				sc.ii.compute(
				    part, ev.cascade().hasTiltedFeatures(), sc.stride);
				ev.setIntegralImages(sc.ii);
				ev.scanWindows(sc.part, step, sc.results);
				for (std::size_t j = 0; j < count; j++)
					sc.accepted[idx[j]] = ev.accepted(sc.results[j]);
			}
		}
		for (std::size_t j = 0; j < windows.size(); j++)
			if (sc.accepted[j])
				found.emplace_back(
				    cvRound(windows[j].x * factor),
				    cvRound(windows[j].y * factor), ws.width, ws.height);
	}
	cv::groupRectangles(found, weights, minNeighbors, 0.2);
}
}  // namespace

std::vector<CascadeDetector::SearchRegion> CascadeDetector::searchRegions(
    const TClassOptions& k, const DetectionPass& pass, cv::Size window,
    const std::vector<ObjectProposal>& proposals, cv::Size imageSize,
    double step) const
{
	std::vector<SearchRegion> out;
	if (pass.rowEnd <= pass.rowBegin || step <= 0) return out;
	const cv::Rect band(
	    0, pass.rowBegin, imageSize.width,
	    std::min(imageSize.height, pass.rowEnd) - pass.rowBegin);
	const double slack = m_options.proposalSizeSlack;
	// The training window is the object's larger side + 15 %.
	const double largest = 1.15 * k.maxSize;
	const double winSide = std::max(window.width, window.height) / pass.upscale;
	for (const auto& p : proposals)
	{
		if (p.nearRange <= 0 || p.farRange <= 0) continue;
		const cv::Rect& box = p.box;
		const double smallest =
		    1.15 * (p.bottom <= m_options.proposalFootHeight ? k.minSize
		                                                     : k.minCutSize);
		double lo = smallest / p.farRange / step / slack;
		double hi = largest / p.nearRange / step * slack;
		lo = std::max({lo, pass.minSide, winSide});
		if (pass.maxSide > 0) hi = std::min(hi, pass.maxSide);
		// A proposal is taken to be (mostly) one object, which fills at
		// least proposal_fill of its larger side (no smaller windows) and
		// lies within it (slack: it may be split).
		const double boxSide = std::max(box.width, box.height);
		lo = std::max(lo, 1.15 * m_options.proposalFill * boxSide / slack);
		hi = std::min(hi, 1.15 * slack * boxSide + 2);
		// Its real size says whether an object of the class can be in it
		// (the 3D size check would reject it anyway): its top is the
		// object's or higher, it is at least as wide as the object and,
		// filling proposal_fill of it, not much wider.
		const double width = box.width * step * p.nearRange;
		if (m_options.proposalSizeCheck &&
		    (p.top < k.minTop || width * slack < k.minWidth ||
		     width * m_options.proposalFill > k.maxWidth * slack))
			continue;
		if (lo > hi) continue;
		const double grow = m_options.proposalMargin * std::min(hi, boxSide);
		cv::Rect2d r(
		    box.x - grow, box.y - grow, box.width + 2 * grow,
		    box.height + 2 * grow);
		// Windows are square: the largest one searched must fit around
		// the box in both directions.
		if (r.width < hi)
		{
			r.x -= (hi - r.width) / 2;
			r.width = hi;
		}
		if (r.height < hi)
		{
			r.y -= (hi - r.height) / 2;
			r.height = hi;
		}
		const cv::Rect ri =
		    cv::Rect(
		        static_cast<int>(std::floor(r.x)),
		        static_cast<int>(std::floor(r.y)),
		        static_cast<int>(std::ceil(r.x + r.width) - std::floor(r.x)),
		        static_cast<int>(std::ceil(r.y + r.height) - std::floor(r.y))) &
		    band;
		if (ri.width < lo || ri.height < lo) continue;
		out.push_back({ri, lo, hi});
	}
	return out;
}

void CascadeDetector::runCascade(
    std::size_t i, const cv::Mat& image, std::vector<cv::Rect>& boxes,
    std::vector<int>& neighbours, const std::vector<ObjectProposal>* proposals,
    double step, const cv::Mat& range, int pass)
{
	const TClassOptions& k = m_options.classes.at(i);
	const cv::Size win = m_impl->windows[i];
	const auto passes = k.passes(image.rows, m_impl->el0, m_impl->el1, win);
	boxes.clear();
	neighbours.clear();
	const cv::Rect all(0, 0, image.cols, image.rows);
	auto& classifier = m_impl->classifiers[i];
	std::vector<cv::Rect> found;
	std::vector<int> n;
	for (std::size_t pi = 0; pi < passes.size(); pi++)
	{
		const DetectionPass& p = passes[pi];
		if (pass >= 0 && pi != std::size_t(pass)) continue;
		if (p.rowEnd <= p.rowBegin) continue;
		if (proposals)
		{
			for (const auto& reg :
			     searchRegions(k, p, win, *proposals, image.size(), step))
			{
				// Scale fitted to the region: upscaled only as far as its
				// smallest object needs to fill the window (at most by the
				// pass's upscale), so no window is wasted on smaller ones.
				const double u =
				    p.upscale <= 1.0
				        ? p.upscale
				        : std::clamp(
				              std::max(win.width, win.height) / reg.minSide,
				              1.0, p.upscale);
				cv::Mat crop = image(reg.rect);
				if (u != 1.0)
					cv::resize(crop, crop, cv::Size(), u, u, cv::INTER_LINEAR);
				const int lo = std::max(
				    {win.width, win.height,
				     static_cast<int>(std::lround(reg.minSide * u))});
				const int hi = std::max(
				    lo, static_cast<int>(std::lround(reg.maxSide * u)));
				found.clear();
				n.clear();
				classifier.detectMultiScale(
				    crop, found, n, k.scaleFactor,
				    k.proposalMinNeighbors < 0 ? k.minNeighbors
				                               : k.proposalMinNeighbors,
				    0, cv::Size(lo, lo), cv::Size(hi, hi));
				n.resize(found.size(), 0);
				for (std::size_t j : fixedOrder(found, n))
				{
					const cv::Rect& f = found[j];
					const int x0 = static_cast<int>(std::floor(f.x / u));
					const int y0 = static_cast<int>(std::floor(f.y / u));
					const int x1 =
					    static_cast<int>(std::ceil((f.x + f.width) / u));
					const int y1 =
					    static_cast<int>(std::ceil((f.y + f.height) / u));
					boxes.push_back(
					    cv::Rect(
					        x0 + reg.rect.x, y0 + reg.rect.y, x1 - x0,
					        y1 - y0) &
					    all);
					neighbours.push_back(n[j]);
				}
			}
			continue;
		}
		// Bands are shared between classes with the same pass.
		// Zero border (as the training samples of objects at the image's
		// edge): left, right and below the lowest elevation.
		const int border =
		    static_cast<int>(std::lround(k.borderPx * p.upscale));
		const int padBelow = p.rowBegin == 0 ? border : 0;
		const auto key = std::make_tuple(
		    m_options.channelOf(k), p.upscale, p.rowBegin, p.rowEnd, border);
		cv::Mat& band = m_impl->scaled.at(slot(i, pi))[key];
		if (band.empty())
		{
			band = p.apply(image);
			if (border > 0)
				cv::copyMakeBorder(
				    band, band, padBelow, 0, border, border,
				    cv::BORDER_CONSTANT, cv::Scalar(0));
		}
		const cv::Size minSize(
		    std::max(
		        win.width,
		        static_cast<int>(std::lround(p.minSide * p.upscale))),
		    std::max(
		        win.height,
		        static_cast<int>(std::lround(p.minSide * p.upscale))));
		cv::Size maxSize;
		if (p.maxSide > 0)
		{
			const int s = static_cast<int>(std::lround(p.maxSide * p.upscale));
			maxSize = cv::Size(s, s);
		}
		found.clear();
		n.clear();
		if (m_options.rangeScales && !range.empty() && step > 0)
		{
			// The band's ranges, scaled and padded as the band.
			cv::Mat r = range.rowRange(
			    std::max(0, p.rowBegin), std::min(range.rows, p.rowEnd));
			if (p.upscale != 1.0)
				cv::resize(
				    r, r, band.size() - cv::Size(2 * border, padBelow), 0, 0,
				    cv::INTER_NEAREST);
			if (border > 0)
				cv::copyMakeBorder(
				    r, r, padBelow, 0, border, border, cv::BORDER_CONSTANT,
				    cv::Scalar(0));
			// Window side w band pixels = w / upscale image pixels: an
			// object of size s (the window's 1 / 1.15) at range
			// s * 1.15 * upscale / (w * step).
			rangeGatedDetect(
			    m_impl->evaluators.at(slot(i, pi)), band, r, k.scaleFactor,
			    k.minNeighbors, k.windowStep, minSize, maxSize,
			    m_options.rangeGate(k, step, p.upscale), found, n,
			    m_impl->gated.at(slot(i, pi)));
		}
		else
			classifier.detectMultiScale(
			    band, found, n, k.scaleFactor, k.minNeighbors, 0, minSize,
			    maxSize);
		n.resize(found.size(), 0);
		for (std::size_t j : fixedOrder(found, n))
		{
			const cv::Rect b =
			    p.toImage(found[j] - cv::Point(border, padBelow)) & all;
			if (b.area() == 0) continue;
			boxes.push_back(b);
			neighbours.push_back(n[j]);
		}
	}
	if (!m_impl->keepScaled)
		for (int pi = 0; pi < kMaxPasses; pi++)
			if (pass < 0 || pi == pass) m_impl->scaled.at(slot(i, pi)).clear();
}

namespace
{
/** measure()'s scratch, per thread (no allocation per candidate once
 * grown). */
struct MeasureScratch
{
	/** Per pixel of the region padded by one on every side (0 on the
	 * border, so that neighbours need no bounds checks): flags. */
	std::vector<uint8_t> state;
	std::vector<double> centreD;
	std::vector<int> queue;
	std::vector<double> lateral;
	std::vector<double> select[2];
	std::vector<uint8_t> buckets;
	std::vector<cv::Point2d> wallXy;
	std::vector<std::size_t> wallAt;
};
thread_local MeasureScratch tlMeasure;

/** std::hypot(x, y) against t > 0 (-1 below, 0 equal, 1 above), mostly
 * without computing it: x^2 + y^2 in double (exact squares of floats, one
 * rounding) decides unless it lies within 1e-6 (relative) of t^2, far
 * beyond the rounding of that sum and hypot's 1 ulp; there hypot itself
 * decides. */
inline int compareHypot(float x, float y, double t)
{
	const double s = double(x) * double(x) + double(y) * double(y);
	const double t2 = t * t;
	if (s < t2 * (1 - 1e-6)) return -1;
	if (s > t2 * (1 + 1e-6)) return 1;
	const double h = std::hypot(double(x), double(y));
	return h < t ? -1 : h > t ? 1 : 0;
}

/** Neighbouring points of one object are at most this far apart (m). */
double connectionGap(const cv::Vec3f& p)
{
	return 0.08 + 0.03 * std::sqrt(p.dot(p));
}
}  // namespace

std::optional<CascadeDetector::Measure> CascadeDetector::measure(
    const cv::Mat& points, const cv::Mat& labels,
    const std::vector<cv::Point>& pixels, const std::vector<cv::Point>& centre,
    double groundZ, double floorTolerance, double maxDepth, int minPoints,
    bool connected, double backWallLength, double rangeLo, double rangeHi)
{
	if (pixels.empty()) return std::nullopt;
	MeasureScratch& sc = tlMeasure;
	const bool hasLabels = !labels.empty();
	const double zFloor = groundZ + floorTolerance;
	const auto pointAt = [&](int x, int y) -> const cv::Vec3f&
	{ return points.ptr<cv::Vec3f>(y)[x]; };
	const auto horizontal = [&](int x, int y)
	{
		const cv::Vec3f& p = pointAt(x, y);
		return std::hypot(double(p[0]), double(p[1]));
	};
	// Not floor (within floorTolerance of the ground) nor a surface. Ground
	// labels (floor, sidewalk, grass) are left to the height test: the
	// rules' ground areas can swallow the top of a low object.
	const auto nonFloor = [&](int x, int y)
	{
		const cv::Vec3f& p = pointAt(x, y);
		if (!(std::isfinite(p[0]) && p[2] >= zFloor)) return false;
		if (rangeHi > 0 &&
		    ((rangeLo > 0 && compareHypot(p[0], p[1], rangeLo) < 0) ||
		     compareHypot(p[0], p[1], rangeHi) > 0))
			return false;
		if (!hasLabels) return true;
		switch (static_cast<Label>(labels.ptr<uint8_t>(y)[x]))
		{
			case Label::Ceiling:
			case Label::Wall:
			case Label::Door:
				return false;
			default:
				return true;
		}
	};
	int x0 = INT_MAX, y0 = INT_MAX, x1 = -1, y1 = -1;
	for (const auto& px : pixels)
	{
		x0 = std::min(x0, px.x);
		y0 = std::min(y0, px.y);
		x1 = std::max(x1, px.x);
		y1 = std::max(y1, px.y);
	}
	const cv::Rect region(x0, y0, x1 - x0 + 1, y1 - y0 + 1);
	// Flags per pixel of the region: one of `pixels`, and not floor or
	// surface; a candidate (not too far behind); kept (connected).
	constexpr uint8_t kIn = 1, kValid = 2, kCand = 4, kKept = 8;
	const int pw = region.width + 2;
	const auto padded = [&](int x, int y)
	{ return std::size_t((y - y0 + 1) * pw + (x - x0 + 1)); };
	std::vector<uint8_t>& state = sc.state;
	state.assign(std::size_t(pw) * std::size_t(region.height + 2), 0);
	for (const auto& px : pixels)
		state[padded(px.x, px.y)] = nonFloor(px.x, px.y) ? kIn | kValid : kIn;
	// How far the object is: the nearest part (10th percentile of the
	// horizontal distance) of the box's centre.
	std::vector<double>& centreD = sc.centreD;
	centreD.clear();
	for (const auto& px : centre)
	{
		const uint8_t f = region.contains(px) ? state[padded(px.x, px.y)] : 0;
		if (f & kIn ? f & kValid : nonFloor(px.x, px.y))
			centreD.push_back(horizontal(px.x, px.y));
	}
	if (centreD.empty())
		for (const auto& px : pixels)
			if (state[padded(px.x, px.y)] & kValid)
				centreD.push_back(horizontal(px.x, px.y));
	if (centreD.empty()) return std::nullopt;
	const double far =
	    percentilesOf(centreD, 0.1, 0.1, sc.select, sc.buckets).first +
	    maxDepth;
	// Candidates: non-floor, non-surface points not too far behind. The
	// object is some of them: too few, and it is too small.
	std::size_t candidates = 0;
	for (const auto& px : pixels)
	{
		uint8_t& f = state[padded(px.x, px.y)];
		const cv::Vec3f& p = pointAt(px.x, px.y);
		if ((f & kValid) && compareHypot(p[0], p[1], far) <= 0)
		{
			f |= kCand;
			candidates++;
		}
	}
	if (static_cast<int>(candidates) < minPoints) return std::nullopt;
	if (backWallLength > 0)
	{
		sc.wallXy.clear();
		sc.wallAt.clear();
		for (const auto& px : pixels)
			if (state[padded(px.x, px.y)] & kCand)
			{
				const cv::Vec3f& p = pointAt(px.x, px.y);
				sc.wallXy.emplace_back(p[0], p[1]);
				sc.wallAt.push_back(padded(px.x, px.y));
			}
		BackWall::Params wp;
		wp.minLength = backWallLength;
		if (const auto wall = BackWall::find(sc.wallXy, wp))
			for (std::size_t i = 0; i < sc.wallXy.size(); i++)
				if (wall->distance(sc.wallXy[i]) >= -wp.tolerance)
					state[sc.wallAt[i]] &= uint8_t(~kCand);
	}
	// Object points, for the reservations below.
	std::size_t kept = 0;
	if (connected)
	{
		// Keep the candidates connected to the centre's: 8-neighbours
		// closer in 3D than a gap growing with the range (the kept set is
		// what the centre reaches, in any visiting order).
		std::vector<int>& queue = sc.queue;
		queue.clear();
		for (const auto& px : centre)
			if (region.contains(px))
			{
				uint8_t& f = state[padded(px.x, px.y)];
				if ((f & (kCand | kKept)) == kCand)
				{
					f |= kKept;
					queue.push_back(int(padded(px.x, px.y)));
				}
			}
		const int offsets[8] = {-pw - 1, -pw,    -pw + 1, -1,
		                        1,       pw - 1, pw,      pw + 1};
		for (std::size_t i = 0; i < queue.size(); i++)
		{
			const int a = queue[i];
			const int ax = a % pw - 1 + x0, ay = a / pw - 1 + y0;
			const cv::Vec3f pa = pointAt(ax, ay);
			const double gap = connectionGap(pa);
			for (int k = 0; k < 8; k++)
			{
				const int b = a + offsets[k];
				uint8_t& f = state[std::size_t(b)];
				if ((f & (kCand | kKept)) != kCand) continue;
				const cv::Vec3f d =
				    pointAt(b % pw - 1 + x0, b / pw - 1 + y0) - pa;
				if (std::sqrt(d.dot(d)) > gap) continue;
				f |= kKept;
				queue.push_back(b);
			}
		}
		kept = queue.size();
	}
	else
		for (const auto& px : pixels)
			kept += (state[padded(px.x, px.y)] & kCand) != 0;
	const uint8_t keep = connected ? kKept : kCand;
	Measure m;
	std::vector<double> xs, ys, zs;
	xs.reserve(kept);
	ys.reserve(kept);
	zs.reserve(kept);
	m.pixels.reserve(kept);
	double sx = 0, sy = 0, sz = 0;
	int c0 = INT_MAX, r0 = INT_MAX, c1 = -1, r1 = -1;
	for (const auto& px : pixels)
	{
		if (!(state[padded(px.x, px.y)] & keep)) continue;
		const cv::Vec3f& p = pointAt(px.x, px.y);
		xs.push_back(p[0]);
		ys.push_back(p[1]);
		zs.push_back(p[2]);
		sx += p[0];
		sy += p[1];
		sz += p[2];
		m.pixels.push_back(px);
		c0 = std::min(c0, px.x);
		c1 = std::max(c1, px.x);
		r0 = std::min(r0, px.y);
		r1 = std::max(r1, px.y);
	}
	m.points = xs.size();
	if (static_cast<int>(m.points) < minPoints) return std::nullopt;
	m.box = cv::Rect(c0, r0, c1 - c0 + 1, r1 - r0 + 1);
	const double n = double(m.points);
	m.centroid = {sx / n, sy / n, sz / n};
	// Extent across the line of sight to the centroid.
	const double bearing = std::atan2(m.centroid.y, m.centroid.x);
	const double sinB = std::sin(bearing), cosB = std::cos(bearing);
	std::vector<double>& lateral = sc.lateral;
	lateral.resize(m.points);
	for (std::size_t i = 0; i < m.points; i++)
		lateral[i] = -sinB * xs[i] + cosB * ys[i];
	// The 5th and 95th percentiles.
	const auto ends = [&](const std::vector<double>& v)
	{ return percentilesOf(v, 0.05, 0.95, sc.select, sc.buckets); };
	const auto spread = [&](const std::vector<double>& v)
	{
		const auto [lo, hi] = ends(v);
		return hi - lo;
	};
	m.width = spread(lateral);
	const auto [zBottom, zTop] = ends(zs);
	m.top = zTop - groundZ;
	m.extent = {spread(xs), spread(ys), zTop - zBottom};
	return m;
}

namespace
{
/** A measured candidate's ObjectShape, with its cascade support if its
 * class uses it (cascade_support), and its steps if `steps`. */
ObjectShape::Features describeCandidate(
    const cv::Mat& points, const cv::Mat& normals, const cv::Mat& normalMask,
    const cv::Mat& labels, const CascadeDetector::TClassOptions& k,
    const CascadeDetector::Candidate& c,
    const std::vector<cv::Point>& surroundings, double groundZ, bool steps)
{
	auto f = ObjectShape::describe(
	    points, normals, normalMask, labels, c.measure->pixels, surroundings,
	    groundZ, steps);
	if (k.cascadeSupport)
		f[ObjectShape::kCascadeSupport] = float(c.cascadeSupport);
	return f;
}

/** The accepted candidates, the highest shape score first, then the most
 * neighbours, then the most points. */
std::vector<std::size_t> acceptedBestFirst(
    const std::vector<CascadeDetector::Candidate>& cands)
{
	std::vector<std::size_t> order;
	for (std::size_t i = 0; i < cands.size(); i++)
		if (cands[i].accepted) order.push_back(i);
	std::stable_sort(
	    order.begin(), order.end(),
	    [&](std::size_t a, std::size_t b)
	    {
		    if (cands[a].shapeScore != cands[b].shapeScore)
			    return cands[a].shapeScore > cands[b].shapeScore;
		    if (cands[a].neighbours != cands[b].neighbours)
			    return cands[a].neighbours > cands[b].neighbours;
		    return cands[a].measure->points > cands[b].measure->points;
	    });
	return order;
}

/** One object, several boxes (detectMultiScale groups similar boxes only):
 * of accepted candidates sharing most object pixels, the first in
 * acceptedBestFirst()'s order that `verify` (the shape check) accepts
 * stays. `verify` runs only on candidates no better one covers. */
template <typename Verify>
void suppressDuplicates(
    std::vector<CascadeDetector::Candidate>& cands, cv::Size size,
    Verify&& verify)
{
	const std::vector<std::size_t> order = acceptedBestFirst(cands);
	cv::Mat taken(size, CV_8U, cv::Scalar(0));
	for (std::size_t i : order)
	{
		auto& c = cands[i];
		std::size_t shared = 0;
		for (const auto& p : c.measure->pixels)
			shared += taken.at<uint8_t>(p) != 0;
		if (2 * shared > c.measure->pixels.size())
		{
			c.accepted = false;
			c.rejection = "duplicate";
			continue;
		}
		if (!verify(c)) continue;
		for (const auto& p : c.measure->pixels) taken.at<uint8_t>(p) = 1;
	}
}

/** One object, boxes on different parts of it: of accepted candidates
 * whose centroids are closer than `separation` (horizontally), the one
 * ranked first by acceptedBestFirst() stays and takes the others' boxes and
 * pixels (an occluder before a flight splits it in parts). */
void suppressNearby(
    std::vector<CascadeDetector::Candidate>& cands, double separation)
{
	std::vector<std::size_t> kept;
	const auto at = [&](std::size_t i)
	{
		return mrpt::math::TPoint2D(
		    cands[i].measure->centroid.x, cands[i].measure->centroid.y);
	};
	for (std::size_t i : acceptedBestFirst(cands))
	{
		const auto near = std::find_if(
		    kept.begin(), kept.end(),
		    [&](std::size_t k) { return (at(k) - at(i)).norm() < separation; });
		if (near == kept.end())
		{
			kept.push_back(i);
			continue;
		}
		auto& c = cands[i];
		c.accepted = false;
		c.rejection = "duplicate";
		// Its part of the object: the kept one's box and pixels cover it.
		auto& m = *cands[*near].measure;
		m.box |= c.measure->box;
		m.pixels.insert(
		    m.pixels.end(), c.measure->pixels.begin(), c.measure->pixels.end());
	}
}
}  // namespace

void CascadeDetector::growObject(
    Candidate& c, const TClassOptions& k, const cv::Mat& points,
    const cv::Mat& labels, double groundZ, double step) const
{
	if (step <= 0) return;
	const Measure& m = *c.measure;
	const double range = std::hypot(m.centroid.x, m.centroid.y);
	const int g = int(std::ceil(k.grow / (std::max(range, 0.5) * step)));
	const cv::Rect grown = cv::Rect(
	                           m.box.x - g, m.box.y - g, m.box.width + 2 * g,
	                           m.box.height + 2 * g) &
	                       cv::Rect(0, 0, points.cols, points.rows);
	std::vector<cv::Point> pixels;
	pixels.reserve(std::size_t(grown.area()));
	for (int r = grown.y; r < grown.y + grown.height; r++)
		for (int col = grown.x; col < grown.x + grown.width; col++)
			pixels.emplace_back(col, r);
	std::vector<double> ranges;
	for (const auto& px : m.pixels)
	{
		const cv::Vec3f& p = points.at<cv::Vec3f>(px);
		ranges.push_back(std::hypot(double(p[0]), double(p[1])));
	}
	// Its points' horizontal ranges, widened: not what lies before it (an
	// occluder) or far behind.
	const auto [nearR, farR] = percentiles(ranges, 0.1, 0.9);
	auto whole = measure(
	    points, labels, pixels, m.pixels, groundZ, m_options.floorTolerance,
	    k.maxDepth, k.minPoints, false, k.backWallLength, nearR - 0.3,
	    farR + 0.5);
	if (!whole || whole->width > k.maxWidth || whole->top > k.maxTop) return;
	// Its box and pixels become the flight's; its centroid and extent stay
	// those its shape was scored on.
	c.measure->box = whole->box;
	c.measure->pixels = std::move(whole->pixels);
}

const std::vector<std::vector<ObjectProposal>>& CascadeDetector::lastProposals()
    const
{
	return m_impl->proposals;
}

const PanoramicProjection& CascadeDetector::projection() const
{
	return m_impl->projection;
}

cv::Mat CascadeDetector::detectionImage(
    const std::vector<double>& phis, const std::vector<double>& thetas,
    const cv::Mat& normals, const cv::Mat& normalMask,
    std::optional<DetectionChannel> channel)
{
	return detectionImage(
	    phis, thetas,
	    DetectionImage::smoothNormals(
	        normals, normalMask, m_options.normalSmoothing),
	    normalMask, channel ? *channel : m_options.channel);
}

cv::Mat CascadeDetector::detectionImage(
    const std::vector<double>& phis, const std::vector<double>& thetas,
    const cv::Mat& smoothed, const cv::Mat& normalMask,
    DetectionChannel channel)
{
	prepareGrid(
	    phis, thetas, smoothed.size(), channel == DetectionChannel::View);
	return gridImage(smoothed, normalMask, channel);
}

void CascadeDetector::prepareGrid(
    const std::vector<double>& phis, const std::vector<double>& thetas,
    cv::Size sweepSize, bool view)
{
	if (!thetas.empty())
	{
		m_impl->el0 = thetas.front();
		m_impl->el1 = thetas.back();
	}
	if (view && (m_impl->rotationPhis != phis ||
	             m_impl->rotationThetas != thetas || m_impl->rotation.empty()))
	{
		if (phis.size() != static_cast<std::size_t>(sweepSize.width) ||
		    thetas.size() != static_cast<std::size_t>(sweepSize.height))
			throw Error(
			    "DetectionImage: the view channel needs one bearing per "
			    "column and one tilt per row");
		m_impl->rotation = DetectionImage::viewRotation(phis, thetas);
		m_impl->rotationPhis = phis;
		m_impl->rotationThetas = thetas;
	}
	if (m_options.panoramic && !m_impl->projection.sameGrid(phis, thetas))
		m_impl->projection = PanoramicProjection(phis, thetas);
}

cv::Mat CascadeDetector::gridImage(
    const cv::Mat& smoothed, const cv::Mat& normalMask,
    DetectionChannel channel) const
{
	const cv::Mat image = DetectionImage::fromSmoothedNormals(
	    smoothed, normalMask, channel,
	    channel == DetectionChannel::View ? m_impl->rotation : cv::Mat());
	if (!m_options.panoramic) return image;
	return m_impl->projection.toPanoramic(image, cv::INTER_LINEAR);
}

std::vector<cv::Mat> CascadeDetector::gateRanges(
    const cv::Mat& points, const cv::Mat& mask, double groundZ) const
{
	const std::size_t nc = m_options.classes.size();
	std::vector<cv::Mat> ranges(nc);
	std::vector<double> tops(nc);
	for (std::size_t i = 0; i < nc; i++)
		tops[i] = m_options.proposalTop(m_options.classes[i]) + groundZ;
	const cv::Mat& nearest = m_impl->projection.nearestSource();
	if (m_options.panoramic && nearest.size() == points.size() &&
	    points.isContinuous() && (mask.empty() || mask.isContinuous()))
	{
		// Panoramic directly, every class in one pass: the nearest sweep
		// pixel's range (PanoramicProjection::toPanoramic's INTER_NEAREST).
		std::vector<float*> d(nc);
		for (std::size_t i = 0; i < nc; i++)
		{
			ranges[i].create(points.size(), CV_32F);
			d[i] = ranges[i].ptr<float>();
		}
		const auto* p = points.ptr<cv::Vec3f>();
		const uint8_t* m = mask.empty() ? nullptr : mask.ptr<uint8_t>();
		const int32_t* src = nearest.ptr<int32_t>();
		for (int j = 0; j < points.rows * points.cols; j++)
		{
			// The horizontal range (0: none) of the points the mask keeps.
			const int k = src[j];
			float h = 0;
			if (k >= 0 && (!m || m[k]) && std::isfinite(p[k][0]) &&
			    std::isfinite(p[k][1]))
				h = std::hypot(p[k][0], p[k][1]);
			for (std::size_t i = 0; i < nc; i++)
				d[i][j] = h > 0 && (!m || p[k][2] <= tops[i]) ? h : 0.f;
		}
		return ranges;
	}
	// Horizontal range of every point (0: none), then each class's.
	cv::Mat1f horizontal(points.size(), 0.f);
	for (int r = 0; r < points.rows; r++)
	{
		const auto* p = points.ptr<cv::Vec3f>(r);
		auto* h = horizontal.ptr<float>(r);
		for (int c = 0; c < points.cols; c++)
			if (std::isfinite(p[c][0]) && std::isfinite(p[c][1]))
				h[c] = std::hypot(p[c][0], p[c][1]);
	}
	for (std::size_t i = 0; i < nc; i++)
	{
		const double top = tops[i];
		cv::Mat range(points.size(), CV_32F, cv::Scalar(0));
		for (int r = 0; r < points.rows; r++)
		{
			const auto* p = points.ptr<cv::Vec3f>(r);
			const auto* h = horizontal.ptr<float>(r);
			const auto* m = mask.empty() ? nullptr : mask.ptr<uint8_t>(r);
			auto* d = range.ptr<float>(r);
			for (int c = 0; c < points.cols; c++)
				if (h[c] > 0 && (!m || (m[c] && p[c][2] <= top))) d[c] = h[c];
		}
		if (m_options.panoramic)
			range = m_impl->projection.toPanoramic(range, cv::INTER_NEAREST);
		ranges[i] = range;
	}
	return ranges;
}

std::vector<std::vector<ObjectProposal>> CascadeDetector::objectSegments(
    const cv::Mat& points, const cv::Mat& objects, double groundZ) const
{
	// One height limit per class (a class without segment candidates gets
	// none: its limit is below the ground).
	std::vector<double> limits;
	for (const auto& k : m_options.classes)
		limits.push_back(k.segmentCandidates ? m_options.proposalTop(k) : -1.0);
	return ObjectProposals::findInMask(
	    points, objects, groundZ,
	    m_options.panoramic ? &m_impl->projection : nullptr, limits,
	    m_options.segmentParams());
}

CascadeDetector::SearchInput CascadeDetector::prepareSearch(
    const std::vector<double>& phis, const std::vector<double>& thetas,
    const cv::Mat& normals, const cv::Mat& normalMask, const cv::Mat& points,
    double groundZ, const cv::Mat& labels, const cv::Mat& areaIds,
    bool withSegments)
{
	const auto t0 = Clock::now();
	m_timings = Timings();
	SearchInput in;
	// One detection image per channel in use, from one smoothing, the
	// range_scales gate's range images and the segments: one parallel step
	// (threads), the longest task first.
	std::vector<DetectionChannel> channels;
	for (const auto& k : m_options.classes)
		if (std::find(
		        channels.begin(), channels.end(), m_options.channelOf(k)) ==
		    channels.end())
			channels.push_back(m_options.channelOf(k));
	prepareGrid(
	    phis, thetas, normals.size(),
	    std::count(channels.begin(), channels.end(), DetectionChannel::View) >
	        0);
	const bool gated = m_options.rangeScales && !m_options.proposals;
	std::vector<cv::Mat> channelImages(channels.size());
	in.ranges.resize(m_options.classes.size());
	// Task times (the tasks may run in parallel).
	double imageMs = 0, rangesMs = 0, segmentsMs = 0;
	const bool segmented =
	    withSegments &&
	    std::any_of(
	        m_options.classes.begin(), m_options.classes.end(),
	        [](const TClassOptions& k) { return k.segmentCandidates; });
	const double prepareMs = msSince(t0);
	// The object points (ObjectProposals::objectMask) the gate ranges and
	// the segments both take, then those: one task beside the images.
	enum class Task
	{
		Images,
		Objects
	};
	std::vector<Task> prepare{Task::Images};
	cv::Mat objects;
	if (segmented || gated) prepare.push_back(Task::Objects);
	parallelFor(
	    prepare.size(), m_options.threads,
	    [&](std::size_t t)
	    {
		    const auto tt = Clock::now();
		    switch (prepare[t])
		    {
			    case Task::Images:
			    {
				    const cv::Mat smoothed = DetectionImage::smoothNormals(
				        normals, normalMask, m_options.normalSmoothing);
				    for (std::size_t c = 0; c < channels.size(); c++)
					    channelImages[c] =
					        gridImage(smoothed, normalMask, channels[c]);
				    imageMs = msSince(tt);
				    break;
			    }
			    case Task::Objects:
			    {
				    if (segmented || m_options.rangeObjectsOnly)
					    objects = ObjectProposals::objectMask(
					        points, labels, areaIds, groundZ,
					        m_options.segmentParams());
				    if (gated)
					    in.ranges = gateRanges(
					        points,
					        m_options.rangeObjectsOnly ? objects : cv::Mat(),
					        groundZ);
				    rangesMs = msSince(tt);
				    const auto ts = Clock::now();
				    if (segmented)
					    in.segments = objectSegments(points, objects, groundZ);
				    segmentsMs = msSince(ts);
				    break;
			    }
		    }
	    });
	for (std::size_t c = 0; c < channels.size(); c++)
		in.images[channels[c]] = channelImages[c];
	m_timings.image = prepareMs + imageMs;
	const auto tp = Clock::now();
	m_impl->proposals.clear();
	// Both layouts keep the sweep's angular steps.
	in.pixelAngle =
	    phis.size() > 1 && thetas.size() > 1
	        ? 0.5 *
	              ((phis.back() - phis.front()) / double(phis.size() - 1) +
	               (thetas.back() - thetas.front()) / double(thetas.size() - 1))
	        : 0;
	in.step = m_options.proposals || gated ? in.pixelAngle : 0;
	if (m_options.proposals)
	{
		std::vector<double> limits;
		for (const auto& k : m_options.classes)
			limits.push_back(m_options.proposalTop(k));
		m_impl->proposals = ObjectProposals::find(
		    points, labels, areaIds, groundZ,
		    m_options.panoramic ? &m_impl->projection : nullptr, limits,
		    m_options.proposalParams(
		        m_options.proposalJoinPx, m_options.proposalRangeGap));
	}
	m_timings.proposals = msSince(tp) + rangesMs + segmentsMs;
	return in;
}

std::vector<CascadeDetector::CascadeBoxes> CascadeDetector::searchCascades(
    const SearchInput& in)
{
	const auto t0 = Clock::now();
	auto out = runSearch(in, 0, [](std::size_t) {});
	m_timings.cascades = 0;
	m_timings.sizeCheck = 0;
	for (const auto& c : out) m_timings.cascades += c.ms;
	m_timings.total = m_timings.image + m_timings.proposals + msSince(t0);
	return out;
}

std::vector<CascadeDetector::CascadeBoxes> CascadeDetector::runSearch(
    const SearchInput& in, std::size_t extraTasks,
    const std::function<void(std::size_t)>& extra)
{
	const bool gated = m_options.rangeScales && !m_options.proposals;
	// A task per class, or per pass where the passes are range-gated (each
	// pass has its own scratch), the larger bands first.
	struct CascadeTask
	{
		std::size_t classIndex = 0;
		int pass = -1;
		double work = 0;
		std::vector<cv::Rect> boxes;
		std::vector<int> neighbours;
		double ms = 0;
	};
	std::vector<CascadeTask> tasks;
	for (std::size_t i = 0; i < m_options.classes.size(); i++)
	{
		const TClassOptions& k = m_options.classes[i];
		const cv::Mat& image = in.images.at(m_options.channelOf(k));
		if (!gated || in.ranges.at(i).empty() || in.step <= 0)
		{
			tasks.push_back({i, -1, HUGE_VAL, {}, {}, 0});
			continue;
		}
		const auto passes =
		    k.passes(image.rows, m_impl->el0, m_impl->el1, m_impl->windows[i]);
		for (std::size_t pi = 0; pi < passes.size(); pi++)
			tasks.push_back(
			    {i,
			     int(pi),
			     (passes[pi].rowEnd - passes[pi].rowBegin) *
			         passes[pi].upscale * passes[pi].upscale,
			     {},
			     {},
			     0});
	}
	std::vector<std::size_t> largestFirst(tasks.size());
	std::iota(largestFirst.begin(), largestFirst.end(), 0);
	std::stable_sort(
	    largestFirst.begin(), largestFirst.end(),
	    [&](std::size_t a, std::size_t b)
	    { return tasks[a].work > tasks[b].work; });
	m_impl->keepScaled = true;
	parallelFor(
	    tasks.size() + extraTasks, m_options.threads,
	    [&](std::size_t t)
	    {
		    if (t >= tasks.size())
		    {
			    extra(t - tasks.size());
			    return;
		    }
		    CascadeTask& task = tasks[largestFirst[t]];
		    const std::size_t i = task.classIndex;
		    const auto tc = Clock::now();
		    runCascade(
		        i, in.images.at(m_options.channelOf(m_options.classes[i])),
		        task.boxes, task.neighbours,
		        m_options.proposals ? &m_impl->proposals.at(i) : nullptr,
		        in.step, in.ranges.at(i), task.pass);
		    task.ms = msSince(tc);
	    });
	for (auto& s : m_impl->scaled) s.clear();
	m_impl->keepScaled = false;
	// Each class's boxes in pass order.
	std::vector<CascadeBoxes> out(m_options.classes.size());
	for (const CascadeTask& task : tasks)
	{
		CascadeBoxes& o = out[task.classIndex];
		o.boxes.insert(o.boxes.end(), task.boxes.begin(), task.boxes.end());
		o.neighbours.insert(
		    o.neighbours.end(), task.neighbours.begin(), task.neighbours.end());
		o.ms += task.ms;
	}
	return out;
}

std::vector<CascadeDetector::Candidate> CascadeDetector::detectCandidates(
    const std::vector<double>& phis, const std::vector<double>& thetas,
    const cv::Mat& normals, const cv::Mat& normalMask, const cv::Mat& points,
    double groundZ, const cv::Mat& labels, const cv::Mat& areaIds)
{
	const auto t0 = Clock::now();
	const SearchInput in = prepareSearch(
	    phis, thetas, normals, normalMask, points, groundZ, labels, areaIds);
	// Three steps, each in parallel (threads), with the same candidates in
	// the order of the classes: the cascades (a class or pass a task) and
	// the segment candidates (a candidate a task: measured and described
	// while the cascades run); the cascade boxes measured and described,
	// and every candidate scored (a candidate a task); the shape check (a
	// class a task: its order matters among duplicates).
	struct ClassResult
	{
		std::vector<Candidate> candidates;
		double cascades = 0, sizeCheck = 0;
	};
	std::vector<ClassResult> results(m_options.classes.size());
	const int threads = m_options.threads;
	// Each class's segment candidates.
	const ObjectProposals::Params segmentParams = m_options.segmentParams();
	std::vector<std::vector<Candidate>> segmentCands(m_options.classes.size());
	std::vector<std::pair<std::size_t, std::size_t>> segmentTasks;
	for (std::size_t i = 0; i < m_options.classes.size(); i++)
	{
		const TClassOptions& k = m_options.classes[i];
		if (!k.segmentCandidates) continue;
		for (const ObjectProposal& p : in.segments.at(i))
		{
			if (p.tallerPixels > m_options.segmentMaxTaller * p.pixels)
				continue;
			Candidate& c = segmentCands[i].emplace_back();
			c.label = k.label;
			c.box = p.box;
			c.fromSegment = true;
			if (m_options.segmentRangeWindow)
			{
				c.rangeLo = p.nearRange - segmentParams.gapAt(p.nearRange);
				c.rangeHi = p.farRange + segmentParams.gapAt(p.farRange);
			}
			segmentTasks.emplace_back(i, segmentCands[i].size() - 1);
		}
	}
	// Measures a candidate of class i, checks its size and describes it
	// (with its cascade support as it is then); returns the time taken.
	const auto measureCandidate = [&](std::size_t i, Candidate& c)
	{
		const auto tm = Clock::now();
		const TClassOptions& k = m_options.classes[i];
		// The centre's pixels in a buffer per thread (the box's are kept
		// for the shape check).
		thread_local std::vector<cv::Point> centre;
		centre.clear();
		std::vector<cv::Point> pixels;
		// The object is measured in the box grown by measure_margin on
		// every side (grouped boxes may cut an object); how far it is, in
		// the box's central half.
		const cv::Rect2d inner(
		    c.box.x + c.box.width / 4.0, c.box.y + c.box.height / 4.0,
		    c.box.width / 2.0, c.box.height / 2.0);
		const double mg = m_options.measureMargin;
		const cv::Rect2d b(
		    c.box.x - mg * c.box.width, c.box.y - mg * c.box.height,
		    c.box.width * (1 + 2 * mg), c.box.height * (1 + 2 * mg));
		if (m_options.panoramic)
			m_impl->projection.sweepPixelsIn(b, inner, pixels, centre);
		else
		{
			const cv::Rect bi =
			    cv::Rect(b) & cv::Rect(0, 0, points.cols, points.rows);
			for (int r = bi.y; r < bi.y + bi.height; r++)
				for (int col = bi.x; col < bi.x + bi.width; col++)
				{
					pixels.emplace_back(col, r);
					if (inner.contains(cv::Point2d(col + 0.5, r + 0.5)))
						centre.emplace_back(col, r);
				}
		}
		c.measure = measure(
		    points, labels, pixels, centre, groundZ, m_options.floorTolerance,
		    k.maxDepth, k.minPoints, m_options.connectedObject,
		    k.backWallLength, c.rangeLo, c.rangeHi);
		if (!c.measure)
			c.rejection = "too few points";
		else if (c.measure->width < k.minWidth)
			c.rejection = "too narrow";
		else if (c.measure->width > k.maxWidth)
			c.rejection = "too wide";
		else if (c.measure->top < k.minTop)
			c.rejection = "too low";
		else if (c.measure->top > k.maxTop)
			c.rejection = "too high";
		else if (
		    k.maxContinuingShare < 1 &&
		    continuingShare(points, labels, *c.measure) > k.maxContinuingShare)
			c.rejection = "taller";
		else
			c.accepted = true;
		if (c.accepted &&
		    (m_impl->describeShapes || !m_impl->verifiers[i].empty()))
			c.shape = describeCandidate(
			    points, normals, normalMask, labels, k, c, pixels, groundZ,
			    m_impl->describeShapes || m_impl->verifiers[i].readsSteps());
		return msSince(tm);
	};
	std::vector<double> segmentMs(segmentTasks.size());
	const std::vector<CascadeBoxes> found = runSearch(
	    in, segmentTasks.size(),
	    [&](std::size_t t)
	    {
		    const auto [i, j] = segmentTasks[t];
		    segmentMs[t] = measureCandidate(i, segmentCands[i][j]);
	    });
	for (std::size_t s = 0; s < segmentTasks.size(); s++)
		results[segmentTasks[s].first].sizeCheck += segmentMs[s];
	// Each class's candidates: its cascade boxes, then its segments (little
	// work: one thread).
	for (std::size_t i = 0; i < results.size(); i++)
	{
		const TClassOptions& k = m_options.classes[i];
		const std::vector<cv::Rect>& boxes = found[i].boxes;
		const std::vector<int>& neighbours = found[i].neighbours;
		results[i].cascades += found[i].ms;
		auto& cands = results[i].candidates;
		cands.resize(boxes.size());
		for (std::size_t j = 0; j < boxes.size(); j++)
		{
			cands[j].label = k.label;
			cands[j].box = boxes[j];
			cands[j].neighbours = neighbours[j];
		}
		std::move(
		    segmentCands[i].begin(), segmentCands[i].end(),
		    std::back_inserter(cands));
		for (auto& c : cands)
			for (std::size_t j = 0; j < boxes.size(); j++)
				if (ObjectScorer::iou(c.box, boxes[j]) >= 0.3)
					c.cascadeSupport += std::max(1, neighbours[j]);
	}
	// The cascade boxes measured and described; every candidate that
	// passed the size check scored (the shape check below compares the
	// scores of the ones duplicates leave).
	std::vector<std::pair<std::size_t, std::size_t>> all;
	for (std::size_t i = 0; i < results.size(); i++)
		for (std::size_t j = 0; j < results[i].candidates.size(); j++)
			all.emplace_back(i, j);
	std::vector<double> measureMs(all.size());
	parallelFor(
	    all.size(), threads,
	    [&](std::size_t a)
	    {
		    const auto [i, j] = all[a];
		    Candidate& c = results[i].candidates[j];
		    const auto tm = Clock::now();
		    if (!c.fromSegment)
			    measureCandidate(i, c);
		    else if (c.shape && m_options.classes[i].cascadeSupport)
			    (*c.shape)[ObjectShape::kCascadeSupport] =
			        float(c.cascadeSupport);
		    const ShapeVerifier& verifier = m_impl->verifiers[i];
		    if (c.accepted && !verifier.empty())
			    c.shapeScore = verifier.score(*c.shape);
		    measureMs[a] = msSince(tm);
	    });
	for (std::size_t a = 0; a < all.size(); a++)
		results[all[a].first].sizeCheck += measureMs[a];
	parallelFor(
	    results.size(), threads,
	    [&](std::size_t i)
	    {
		    const auto tm = Clock::now();
		    const TClassOptions& k = m_options.classes[i];
		    auto& out = results[i].candidates;
		    // The shape check, on the candidates duplicates do not remove.
		    suppressDuplicates(
		        out, points.size(),
		        [&](Candidate& c)
		        {
			        if (m_impl->verifiers[i].empty() ||
			            c.shapeScore >= k.minShapeScore)
				        return true;
			        c.accepted = false;
			        c.rejection = "shape";
			        return false;
		        });
		    if (k.minSeparation > 0) suppressNearby(out, k.minSeparation);
		    if (k.grow > 0)
			    for (auto& c : out)
				    if (c.accepted)
					    growObject(
					        c, k, points, labels, groundZ, in.pixelAngle);
		    results[i].sizeCheck += msSince(tm);
	    });
	std::vector<Candidate> out;
	for (auto& r : results)
	{
		m_timings.cascades += r.cascades;
		m_timings.sizeCheck += r.sizeCheck;
		std::move(
		    r.candidates.begin(), r.candidates.end(), std::back_inserter(out));
	}
	m_timings.total = msSince(t0);
	return out;
}

double CascadeDetector::continuingShare(
    const cv::Mat& points, const cv::Mat& labels, const Measure& m)
{
	// The highest object pixel of each column.
	std::vector<int> top(std::size_t(std::max(0, m.box.width)), -1);
	for (const auto& p : m.pixels)
	{
		int& t = top[std::size_t(p.x - m.box.x)];
		t = std::max(t, p.y);
	}
	int columns = 0, continuing = 0;
	for (std::size_t i = 0; i < top.size(); i++)
	{
		const int row = top[i];
		if (row < 0) continue;
		columns++;
		const int col = m.box.x + int(i);
		const cv::Vec3f a = points.at<cv::Vec3f>(row, col);
		const double gap = connectionGap(a);
		for (int r = row + 1; r <= std::min(points.rows - 1, row + 3); r++)
		{
			const cv::Vec3f b = points.at<cv::Vec3f>(r, col);
			if (!std::isfinite(b[0]) || b[2] < a[2] + 0.02f) continue;
			if (!labels.empty() && static_cast<Label>(labels.at<uint8_t>(
			                           r, col)) == Label::Ceiling)
				continue;
			const cv::Vec3f d = b - a;
			if (std::sqrt(double(d.dot(d))) <= gap)
			{
				continuing++;
				break;
			}
		}
	}
	return columns ? double(continuing) / columns : 0;
}

void CascadeDetector::detect(const Sweep& sweep, LabeledSweep& ls)
{
	if (ls.normals.empty()) return;
	const auto cands = detectCandidates(
	    sweep.phis(), sweep.thetas(), ls.normals, ls.normalMask, ls.points,
	    ls.groundZ, ls.labels, ls.areaIds);
	for (const auto& c : cands)
	{
		if (!c.accepted) continue;
		Detection d;
		d.label = c.label;
		d.imageBox = c.measure->box;
		d.centroid = c.measure->centroid;
		d.extent = c.measure->extent;
		d.score = c.neighbours;
		d.shapeScore = c.shapeScore;
		ls.detections.push_back(d);
		if (m_options.labelPixels && !ls.labels.empty())
			for (const auto& p : c.measure->pixels)
				ls.labels.at<uint8_t>(p) = static_cast<uint8_t>(c.label);
	}
}

}  // namespace semnav
