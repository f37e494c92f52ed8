/* semnav: semantic navigation from tilting-laser sweeps */
/* CascadeDetector: loading the cascades, the detection images, and
 * detectCandidates()'s steps (search: CascadeSearch.cpp and
 * RangeGatedSearch.cpp; 3D measurement: CascadeMeasure.cpp), then the
 * shape check and the suppression of duplicates. */
#include <semnav/cascade/CascadeError.h>
#include <semnav/cascade/CascadeXml.h>
#include <semnav/common/Error.h>
#include <semnav/common/ParallelFor.h>
#include <semnav/common/Timing.h>
#include <semnav/detection/BoxOverlap.h>
#include <semnav/detection/CascadeDetector.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <opencv2/imgproc.hpp>

#include "CascadeDetectorImpl.h"

namespace semnav
{
using namespace cascade_detector;

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

std::vector<CascadeDetector::Candidate> CascadeDetector::detectCandidates(
    const std::vector<double>& phis, const std::vector<double>& thetas,
    const cv::Mat& normals, const cv::Mat& normalMask, const cv::Mat& points,
    double groundZ, const cv::Mat& labels, const cv::Mat& areaIds)
{
	const auto t0 = Clock::now();
	const SearchInput in = prepareSearch(
	    phis, thetas, normals, normalMask, points, groundZ, labels, areaIds);
	const SweepImages sweep{normals, normalMask, points, labels, groundZ};
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
	// Each class's segment candidates.
	std::vector<std::vector<Candidate>> segmentCands;
	std::vector<std::pair<std::size_t, std::size_t>> segmentTasks;
	segmentCandidates(in, segmentCands, segmentTasks);
	// The cascades, and beside them the segment candidates measured.
	std::vector<double> segmentMs(segmentTasks.size());
	const std::vector<CascadeBoxes> found = runSearch(
	    in, segmentTasks.size(),
	    [&](std::size_t t)
	    {
		    const auto [i, j] = segmentTasks[t];
		    segmentMs[t] = measureCandidate(i, segmentCands[i][j], sweep);
	    });
	for (std::size_t s = 0; s < segmentTasks.size(); s++)
		results[segmentTasks[s].first].sizeCheck += segmentMs[s];
	// Each class's candidates: its cascade boxes, then its segments (little
	// work: one thread).
	for (std::size_t i = 0; i < results.size(); i++)
	{
		results[i].cascades += found[i].ms;
		results[i].candidates = classCandidates(i, found[i], segmentCands[i]);
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
	    all.size(), m_options.threads,
	    [&](std::size_t a)
	    {
		    const auto [i, j] = all[a];
		    Candidate& c = results[i].candidates[j];
		    const auto tm = Clock::now();
		    if (!c.fromSegment)
			    measureCandidate(i, c, sweep);
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
	// The shape check and the suppression of duplicates.
	parallelFor(
	    results.size(), m_options.threads,
	    [&](std::size_t i)
	    {
		    const auto tm = Clock::now();
		    finishCandidates(i, results[i].candidates, sweep, in.pixelAngle);
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

void CascadeDetector::segmentCandidates(
    const SearchInput& in, std::vector<std::vector<Candidate>>& segmentCands,
    std::vector<std::pair<std::size_t, std::size_t>>& segmentTasks) const
{
	const ObjectProposals::Params segmentParams = m_options.segmentParams();
	segmentCands.assign(m_options.classes.size(), {});
	segmentTasks.clear();
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
}

double CascadeDetector::measureCandidate(
    std::size_t i, Candidate& c, const SweepImages& sweep) const
{
	const cv::Mat &points = sweep.points, &labels = sweep.labels;
	const double groundZ = sweep.groundZ;
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
	    k.maxDepth, k.minPoints, m_options.connectedObject, k.backWallLength,
	    c.rangeLo, c.rangeHi);
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
	else if (
	    k.maxOverheadShare < 1 &&
	    overheadShare(points, labels, *c.measure, groundZ) > k.maxOverheadShare)
		c.rejection = "under something";
	else if (
	    k.minFlatFaceShare > 0 &&
	    (c.flatFaceShare = flatFaceShare(points, *c.measure, groundZ)) &&
	    *c.flatFaceShare < k.minFlatFaceShare)
		c.rejection = "round";
	else
		c.accepted = true;
	if (c.accepted && (m_impl->describeShapes || !m_impl->verifiers[i].empty()))
		c.shape = describeCandidate(
		    points, sweep.normals, sweep.normalMask, labels, k, c, pixels,
		    groundZ,
		    m_impl->describeShapes || m_impl->verifiers[i].readsSteps());
	return msSince(tm);
}

std::vector<CascadeDetector::Candidate> CascadeDetector::classCandidates(
    std::size_t i, const CascadeBoxes& found,
    std::vector<Candidate>& segments) const
{
	const TClassOptions& k = m_options.classes[i];
	const std::vector<cv::Rect>& boxes = found.boxes;
	const std::vector<int>& neighbours = found.neighbours;
	std::vector<Candidate> cands(boxes.size());
	for (std::size_t j = 0; j < boxes.size(); j++)
	{
		cands[j].label = k.label;
		cands[j].box = boxes[j];
		cands[j].neighbours = neighbours[j];
	}
	std::move(segments.begin(), segments.end(), std::back_inserter(cands));
	for (auto& c : cands)
		for (std::size_t j = 0; j < boxes.size(); j++)
			if (boxIou(c.box, boxes[j]) >= 0.3)
				c.cascadeSupport += std::max(1, neighbours[j]);
	return cands;
}

void CascadeDetector::finishCandidates(
    std::size_t i, std::vector<Candidate>& out, const SweepImages& sweep,
    double pixelAngle) const
{
	const TClassOptions& k = m_options.classes[i];
	// The shape check, on the candidates duplicates do not remove.
	suppressDuplicates(
	    out, sweep.points.size(),
	    [&](Candidate& c)
	    {
		    if (m_impl->verifiers[i].empty() ||
		        c.shapeScore >=
		            k.minShapeScoreAt(std::atan2(
		                c.measure->centroid.y, c.measure->centroid.x)))
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
				    c, k, sweep.points, sweep.labels, sweep.groundZ,
				    pixelAngle);
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