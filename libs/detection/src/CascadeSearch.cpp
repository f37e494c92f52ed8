/* semnav: semantic navigation from tilting-laser sweeps */
/* CascadeDetector's cascade search: the detection images and range images
 * of a sweep (prepareSearch), the search regions around proposals, each
 * class's passes (runCascade) and the parallel search (runSearch). */
#include <semnav/common/ParallelFor.h>
#include <semnav/common/Timing.h>
#include <semnav/detection/CascadeDetector.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <opencv2/imgproc.hpp>
#include <tuple>

#include "CascadeDetectorImpl.h"

namespace semnav
{
using namespace cascade_detector;

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
	for (std::size_t pi = 0; pi < passes.size(); pi++)
	{
		const DetectionPass& p = passes[pi];
		if (pass >= 0 && pi != std::size_t(pass)) continue;
		if (p.rowEnd <= p.rowBegin) continue;
		if (proposals)
			searchProposals(i, p, image, *proposals, step, boxes, neighbours);
		else
			searchBand(i, pi, p, image, range, step, boxes, neighbours);
	}
	if (!m_impl->keepScaled)
		for (int pi = 0; pi < kMaxPasses; pi++)
			if (pass < 0 || pi == pass) m_impl->scaled.at(slot(i, pi)).clear();
}

void CascadeDetector::searchProposals(
    std::size_t i, const DetectionPass& p, const cv::Mat& image,
    const std::vector<ObjectProposal>& proposals, double step,
    std::vector<cv::Rect>& boxes, std::vector<int>& neighbours)
{
	const TClassOptions& k = m_options.classes.at(i);
	const cv::Size win = m_impl->windows[i];
	const cv::Rect all(0, 0, image.cols, image.rows);
	auto& classifier = m_impl->classifiers[i];
	std::vector<cv::Rect> found;
	std::vector<int> n;
	for (const auto& reg :
	     searchRegions(k, p, win, proposals, image.size(), step))
	{
		// Scale fitted to the region: upscaled only as far as its
		// smallest object needs to fill the window (at most by the
		// pass's upscale), so no window is wasted on smaller ones.
		const double u =
		    p.upscale <= 1.0
		        ? p.upscale
		        : std::clamp(
		              std::max(win.width, win.height) / reg.minSide, 1.0,
		              p.upscale);
		cv::Mat crop = image(reg.rect);
		if (u != 1.0)
			cv::resize(crop, crop, cv::Size(), u, u, cv::INTER_LINEAR);
		const int lo = std::max(
		    {win.width, win.height,
		     static_cast<int>(std::lround(reg.minSide * u))});
		const int hi =
		    std::max(lo, static_cast<int>(std::lround(reg.maxSide * u)));
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
			const int x1 = static_cast<int>(std::ceil((f.x + f.width) / u));
			const int y1 = static_cast<int>(std::ceil((f.y + f.height) / u));
			boxes.push_back(
			    cv::Rect(x0 + reg.rect.x, y0 + reg.rect.y, x1 - x0, y1 - y0) &
			    all);
			neighbours.push_back(n[j]);
		}
	}
}

void CascadeDetector::searchBand(
    std::size_t i, std::size_t pi, const DetectionPass& p, const cv::Mat& image,
    const cv::Mat& range, double step, std::vector<cv::Rect>& boxes,
    std::vector<int>& neighbours)
{
	const TClassOptions& k = m_options.classes.at(i);
	const cv::Rect all(0, 0, image.cols, image.rows);
	const cv::Size win = m_impl->windows[i];
	auto& classifier = m_impl->classifiers[i];
	std::vector<cv::Rect> found;
	std::vector<int> n;
	// Bands are shared between classes with the same pass.
	// Zero border (as the training samples of objects at the image's
	// edge): left, right and below the lowest elevation.
	const int border = static_cast<int>(std::lround(k.borderPx * p.upscale));
	const int padBelow = p.rowBegin == 0 ? border : 0;
	const auto key = std::make_tuple(
	    m_options.channelOf(k), p.upscale, p.rowBegin, p.rowEnd, border);
	cv::Mat& band = m_impl->scaled.at(slot(i, pi))[key];
	if (band.empty())
	{
		band = p.apply(image);
		if (border > 0)
			cv::copyMakeBorder(
			    band, band, padBelow, 0, border, border, cv::BORDER_CONSTANT,
			    cv::Scalar(0));
	}
	const cv::Size minSize(
	    std::max(
	        win.width, static_cast<int>(std::lround(p.minSide * p.upscale))),
	    std::max(
	        win.height, static_cast<int>(std::lround(p.minSide * p.upscale))));
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
		detail::rangeGatedDetect(
		    m_impl->evaluators.at(slot(i, pi)), band, r, k.scaleFactor,
		    k.minNeighbors, k.windowStep, minSize, maxSize,
		    m_options.rangeGate(k, step, p.upscale), found, n,
		    m_impl->gated.at(slot(i, pi)));
	}
	else
		classifier.detectMultiScale(
		    band, found, n, k.scaleFactor, k.minNeighbors, 0, minSize, maxSize);
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

}  // namespace semnav
