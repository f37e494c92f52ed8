/* semnav: semantic navigation from tilting-laser sweeps */
// StopAndScanLocalizer: what decides a start (the uniqueness check, the
// evidence carried across drives to look, contradictions with the map, the
// hypotheses to tell apart).
#include <mrpt/core/format.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/poses/CPose3D.h>
#include <semnav/common/Error.h>
#include <semnav/common/OptionTable.h>
#include <semnav/common/Timing.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/map/SweepView.h>
#include <semnav/nav/NavigationErrors.h>
#include <semnav/nav/OdometryMotion.h>
#include <semnav/nav/StopAndScanLocalizer.h>
#include <semnav/robot/ControlClock.h>
#include <semnav/robot/LocalizedPose.h>
#include <semnav/robot/PoseSource.h>
#include <semnav/robot/RobotBase.h>
#include <semnav/scan/SweepSource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace semnav
{
namespace
{
/** Particles this close (m, rad) to a cluster's seed belong to it. */
constexpr double kHypothesisRadius = 0.5;
const double kHypothesisYaw = mrpt::DEG2RAD(20.0);
/** Clusters lighter than this share of the weight are not hypotheses. */
constexpr double kHypothesisMinWeight = 0.03;
constexpr std::size_t kMaxHypotheses = 4;
/** A hypothesis after a drive is the one before it carried by the drive's
 * odometry when this close (m, rad): the odometry drifts on the way. */
constexpr double kCarriedRadius = 0.75;
const double kCarriedYaw = mrpt::DEG2RAD(20.0);
/** Detections of one label this close (m) in two sweeps are one object. */
constexpr double kSameObject = 0.5;
/** A map object is detected by a sweep that found its label this close. */
constexpr double kMissRadius = 1.0;
/** Bounds of an instance's recall (detections per view) for a miss. */
constexpr double kMinRecall = 0.3, kMaxRecall = 0.8;

/** Closer than `radius` (m) and `yaw` (rad). */
bool closeTo(
    const mrpt::math::TPose2D& a, const mrpt::math::TPose2D& b, double radius,
    double yaw)
{
	return std::hypot(a.x - b.x, a.y - b.y) < radius &&
	       std::abs(mrpt::math::wrapToPi(a.phi - b.phi)) < yaw;
}
}  // namespace

std::vector<ViewPlanner::Hypothesis> StopAndScanLocalizer::hypotheses(
    const SweepRecord& rec) const
{
	// Greedy clusters of the particles, heaviest first.
	const auto& ps = m_localizer->pdf().m_particles;
	std::vector<std::size_t> order(ps.size());
	for (std::size_t i = 0; i < ps.size(); i++) order[i] = i;
	std::sort(
	    order.begin(), order.end(),
	    [&](std::size_t a, std::size_t b)
	    { return ps[a].log_w > ps[b].log_w; });
	const double maxLog = ps.empty() ? 0 : ps[order[0]].log_w;
	double total = 0;
	for (const auto& p : ps) total += std::exp(p.log_w - maxLog);
	const auto near =
	    [](const mrpt::math::TPose2D& a, const mrpt::math::TPose2D& b)
	{ return closeTo(a, b, kHypothesisRadius, kHypothesisYaw); };
	std::vector<ViewPlanner::Hypothesis> h{{rec.estimate, 0}};
	std::vector<char> taken(ps.size(), 0);
	for (int cluster = 0; cluster < 8; cluster++)
	{
		const auto seed = std::find_if(
		    order.begin(), order.end(),
		    [&](std::size_t i) { return !taken[i]; });
		if (seed == order.end()) break;
		const mrpt::math::TPose2D centre = ps[*seed].d;
		double w = 0;
		for (std::size_t i : order)
			if (!taken[i] && near(ps[i].d, centre))
				taken[i] = 1, w += std::exp(ps[i].log_w - maxLog);
		w /= total;
		if (near(centre, rec.estimate))
			h[0].weight += w;
		else if (w >= kHypothesisMinWeight)
			h.push_back({centre, w});
	}
	if (rec.checked && std::none_of(
	                       h.begin(), h.end(),
	                       [&](const ViewPlanner::Hypothesis& o)
	                       { return near(o.pose, rec.rival); }))
		h.push_back({rec.rival, std::max(h[0].weight, kHypothesisMinWeight)});
	if (h.size() > kMaxHypotheses) h.resize(kMaxHypotheses);
	return h;
}

namespace
{
/** Places refined in the uniqueness check. */
constexpr std::size_t kRivals = 8;
using ScoredPose = std::pair<double, mrpt::math::TPose2D>;

/** Adds `c` to the best-first `top` (at most kRivals). `distinct`: one per
 * hypothesis (a better place within kHypothesisRadius and kHypothesisYaw
 * replaces its neighbour). */
void keepBest(std::vector<ScoredPose>& top, const ScoredPose& c, bool distinct)
{
	if (top.size() >= kRivals && c.first <= top.back().first) return;
	const auto near = std::find_if(
	    top.begin(), top.end(),
	    [&](const ScoredPose& t) {
		    return closeTo(
		        t.second, c.second, kHypothesisRadius, kHypothesisYaw);
	    });
	if (distinct && near != top.end())
	{
		if (near->first >= c.first) return;
		top.erase(near);
	}
	top.insert(
	    std::upper_bound(
	        top.begin(), top.end(), c,
	        [](const ScoredPose& a, const ScoredPose& b)
	        { return a.first > b.first; }),
	    c);
	if (top.size() > kRivals) top.pop_back();
}
}  // namespace

void StopAndScanLocalizer::checkUniqueness(SweepRecord& rec) const
{
	const auto t0 = std::chrono::steady_clock::now();
	// Every sweep's samples in the frame of the last sweep's robot pose
	// (odometry between them).
	const mrpt::poses::CPose2D last(m_startOdo.back());
	std::vector<mrpt::math::TPoint2D> pts;
	for (std::size_t i = 0; i < m_startObs.size(); i++)
	{
		const mrpt::poses::CPose2D rel =
		    mrpt::poses::CPose2D(m_startOdo[i]) - last;
		for (const auto& p : m_startObs[i].samples)
		{
			double x, y;
			rel.composePoint(p.x, p.y, x, y);
			pts.push_back({x, y});
		}
	}
	if (pts.empty()) return;
	const WallMap& walls = scoredWalls();
	const double n = static_cast<double>(pts.size());
	const std::size_t minKnown = static_cast<std::size_t>(
	    std::ceil(m_options.uniquenessMinKnownFraction * n));
	// Mean over the samples in observed cells.
	const auto wallScore = [&](double x, double y, double yaw)
	{
		std::size_t known = 0;
		const double sum = walls.knownLogLikelihood(x, y, yaw, pts, known);
		return known >= std::max<std::size_t>(minKnown, 1)
		           ? sum / double(known)
		           : -std::numeric_limits<double>::infinity();
	};
	// The semantic terms of every sweep at its pose, in units of one
	// effective wall point per sweep (as the filter weighs them).
	std::vector<mrpt::poses::CPose2D> rels;
	for (const auto& o : m_startOdo)
		rels.push_back(mrpt::poses::CPose2D(o) - last);
	const double semanticScale =
	    1.0 / (m_locOptions.localizer.effectivePoints * double(rels.size()));
	const auto semanticScore = [&](double x, double y, double yaw)
	{
		if (m_semantic.empty()) return 0.0;
		double sum = 0;
		const mrpt::poses::CPose2D at(x, y, yaw);
		for (std::size_t i = 0; i < rels.size(); i++)
		{
			const mrpt::poses::CPose2D p = at + rels[i];
			sum +=
			    m_semantic.knownTerms(p.x(), p.y(), p.phi(), m_startSemantic[i])
			        .total();
		}
		return sum * semanticScale;
	};
	const auto score = [&](double x, double y, double yaw)
	{ return wallScore(x, y, yaw) + semanticScore(x, y, yaw); };
	// Best pose near `p` (local refinement: +-10 cm, +-1 deg).
	const auto refine = [&](mrpt::math::TPose2D p)
	{
		double best = score(p.x, p.y, p.phi);
		mrpt::math::TPose2D arg = p;
		for (double dx = -0.1; dx <= 0.101; dx += 0.025)
			for (double dy = -0.1; dy <= 0.101; dy += 0.025)
				for (double da = -1; da <= 1.01; da += 0.5)
				{
					const double v =
					    score(p.x + dx, p.y + dy, p.phi + mrpt::DEG2RAD(da));
					if (v > best)
						best = v,
						arg = {p.x + dx, p.y + dy, p.phi + mrpt::DEG2RAD(da)};
				}
		return std::make_pair(best, arg);
	};
	const mrpt::math::TPose2D e = rec.estimate;
	{
		const auto [v, at] = refine(e);
		int missed = 0;
		const double m = missedObjects(at, missed);
		rec.score = v + m;
		if (isLoggingLevelVisible(mrpt::system::LVL_INFO))
			MRPT_LOG_INFO_FMT(
			    "uniqueness: at the estimate walls %.3f, semantics %.3f, "
			    "%d objects missed %.3f",
			    wallScore(at.x, at.y, at.phi),
			    semanticScore(at.x, at.y, at.phi), missed, m);
	}
	// Coarse search away from the estimate.
	const double minD2 =
	    m_options.uniquenessMinDistance * m_options.uniquenessMinDistance;
	// The best places (refining several neighbours of one finds its best
	// pose), and the best of each hypothesis (else the neighbours of one
	// twin fill the list and the twin the missed objects favour is never
	// refined).
	std::vector<ScoredPose> top, distinct;
	for (int k = 0; k < 4; k++)
		for (int j = -2; j <= 2; j++)
		{
			const double yaw = e.phi + k * M_PI / 2 + mrpt::DEG2RAD(double(j));
			for (const auto& q : m_places)
			{
				const double dx = q.x - e.x, dy = q.y - e.y;
				if (k == 0 && dx * dx + dy * dy < minD2) continue;
				const ScoredPose c{score(q.x, q.y, yaw), {q.x, q.y, yaw}};
				keepBest(top, c, false);
				keepBest(distinct, c, true);
			}
		}
	for (const ScoredPose& d : distinct)
		if (std::none_of(
		        top.begin(), top.end(),
		        [&](const ScoredPose& t)
		        { return closeTo(t.second, d.second, 1e-6, 1e-6); }))
			top.push_back(d);
	rec.rivalScore = -std::numeric_limits<double>::infinity();
	int rivalMissed = 0;
	for (const auto& t : top)
	{
		const auto [v, p] = refine(t.second);
		int missed = 0;
		const double total = v + missedObjects(p, missed);
		if (total > rec.rivalScore)
			rec.rivalScore = total, rec.rival = p, rivalMissed = missed;
	}
	if (isLoggingLevelVisible(mrpt::system::LVL_INFO))
		MRPT_LOG_INFO_FMT(
		    "uniqueness: rival (%.2f, %.2f, %.0f deg) %.3f, %d objects missed",
		    rec.rival.x, rec.rival.y, mrpt::RAD2DEG(rec.rival.phi),
		    rec.rivalScore, rivalMissed);
	rec.rival.phi = mrpt::math::wrapToPi(rec.rival.phi);
	rec.checked = true;
	rec.checkMs = msSince(t0);
}

std::string StopAndScanLocalizer::contradiction(
    const mrpt::math::TPose2D& estimate) const
{
	if (m_options.contradictionDistance <= 0 || m_startSemantic.empty())
		return {};
	// Every start sweep's detections in the world at the estimate.
	const mrpt::poses::CPose2D last(m_startOdo.back());
	struct Seen
	{
		std::size_t sweep;
		Label label;
		mrpt::math::TPoint2D at;
	};
	std::vector<Seen> seen;
	for (std::size_t i = 0; i < m_startSemantic.size(); i++)
	{
		const mrpt::poses::CPose2D at =
		    mrpt::poses::CPose2D(estimate) +
		    (mrpt::poses::CPose2D(m_startOdo[i]) - last);
		for (const auto& o : m_startSemantic[i].objects)
		{
			double x, y;
			at.composePoint(o.x, o.y, x, y);
			seen.push_back({i, o.label, {x, y}});
		}
	}
	const auto& g = m_map.geometry();
	for (const Seen& a : seen)
	{
		// Seen again by another sweep at the same place, or by the last
		// sweep (no later one could check it yet): not a one-off.
		const bool twice = std::any_of(
		    seen.begin(), seen.end(),
		    [&](const Seen& b)
		    {
			    return b.sweep != a.sweep && b.label == a.label &&
			           std::hypot(b.at.x - a.at.x, b.at.y - a.at.y) <
			               kSameObject;
		    });
		const bool latest = a.sweep + 1 == m_startSemantic.size();
		int cx, cy;
		if (!(twice || latest) || !g.worldToCell(a.at.x, a.at.y, cx, cy) ||
		    m_map.at("observations", cx, cy) <= 0)
			continue;
		// Any instance the map holds, reported or still a candidate (seen
		// too seldom to report): the map saw something there.
		double d = std::numeric_limits<double>::infinity();
		for (const ObjectInstance& o : m_map.allInstances())
			if (o.label == a.label)
				d = std::min(
				    d,
				    std::hypot(o.centroid.x - a.at.x, o.centroid.y - a.at.y));
		if (d > m_options.contradictionDistance)
			return mrpt::format(
			    "a %s seen%s at (%.2f, %.2f) if the robot stands at (%.2f, "
			    "%.2f, %.0f deg), where the map observed no %s within %.1f m",
			    labelName(a.label).c_str(), twice ? " twice" : "", a.at.x,
			    a.at.y, estimate.x, estimate.y, mrpt::RAD2DEG(estimate.phi),
			    labelName(a.label).c_str(), m_options.contradictionDistance);
	}
	return {};
}

double StopAndScanLocalizer::missedObjects(
    const mrpt::math::TPose2D& at, int& missed) const
{
	missed = 0;
	const double weight = m_options.missedObjectWeight;
	if (weight <= 0 || m_semantic.empty() || m_startSweeps.empty()) return 0;
	const auto& mo = m_map.options();
	// Only what the detectors can find can be missed.
	const std::vector<Label> detectable = m_perception.objectLabels();
	std::vector<ObjectInstance> objects;
	for (const ObjectInstance& o : m_map.instances())
		if (std::find(detectable.begin(), detectable.end(), o.label) !=
		    detectable.end())
			objects.push_back(o);
	if (objects.empty()) return 0;
	const mrpt::poses::CPose2D last(m_startOdo.back());
	double sum = 0;
	for (std::size_t i = 0; i < m_startSweeps.size(); i++)
	{
		const SweepView view(
		    m_startSweeps[i], mrpt::DEG2RAD(mo.viewMaxBearingDeg),
		    mo.viewMinPixels);
		const mrpt::poses::CPose3D robot(
		    mrpt::poses::CPose2D(at) +
		    (mrpt::poses::CPose2D(m_startOdo[i]) - last));
		for (const ObjectInstance& o : objects)
		{
			mrpt::math::TPoint3D p;
			robot.inverseComposePoint(o.centroid, p);
			if (!view.sees(p, o.typicalSize())) continue;
			const bool detected = std::any_of(
			    m_startSemantic[i].objects.begin(),
			    m_startSemantic[i].objects.end(),
			    [&](const SemanticSample& d)
			    {
				    return d.label == o.label &&
				           std::hypot(d.x - p.x, d.y - p.y) < kMissRadius;
			    });
			if (detected) continue;
			const double recall = std::clamp(
			    double(o.observations + 1) / double(o.views + 2), kMinRecall,
			    kMaxRecall);
			sum += std::log(1 - recall);
			missed++;
		}
	}
	return weight * sum /
	       (m_locOptions.localizer.effectivePoints *
	        double(m_startSweeps.size()));
}

mrpt::math::TPose2D StopAndScanLocalizer::carriedTo(
    const mrpt::math::TPose2D& p, const SweepRecord& rec) const
{
	const mrpt::poses::CPose2D drive = mrpt::poses::CPose2D(rec.odometry) -
	                                   mrpt::poses::CPose2D(m_carried.odometry);
	return (mrpt::poses::CPose2D(p) + drive).asTPose();
}

double StopAndScanLocalizer::evidenceOf(const SweepRecord& rec) const
{
	double e = rec.score - rec.rivalScore;
	if (!m_carried.valid) return e;
	const auto near =
	    [](const mrpt::math::TPose2D& a, const mrpt::math::TPose2D& b)
	{ return closeTo(a, b, kCarriedRadius, kCarriedYaw); };
	const auto est = carriedTo(m_carried.estimate, rec),
	           riv = carriedTo(m_carried.rival, rec);
	if (near(rec.estimate, est) && near(rec.rival, riv))
		e += m_carried.evidence;
	else if (near(rec.estimate, riv) && near(rec.rival, est))
		e -= m_carried.evidence;
	return e;
}

std::string StopAndScanLocalizer::carriedContradiction(
    const SweepRecord& rec) const
{
	if (!m_carried.valid || m_carried.contradiction.empty()) return {};
	if (!closeTo(
	        rec.estimate, carriedTo(m_carried.estimate, rec), kCarriedRadius,
	        kCarriedYaw))
		return {};
	return m_carried.contradiction + " (before the drive to look)";
}

double StopAndScanLocalizer::massNear(const mrpt::math::TPose2D& e) const
{
	const auto& ps = m_localizer->pdf().m_particles;
	if (ps.empty()) return 0;
	double maxLog = -std::numeric_limits<double>::infinity();
	for (const auto& p : ps) maxLog = std::max(maxLog, p.log_w);
	double total = 0, near = 0;
	const double r2 = m_options.convergedRadius * m_options.convergedRadius;
	for (const auto& p : ps)
	{
		const double w = std::exp(p.log_w - maxLog);
		total += w;
		const double dx = p.d.x - e.x, dy = p.d.y - e.y;
		if (dx * dx + dy * dy <= r2 &&
		    std::abs(mrpt::math::wrapToPi(p.d.phi - e.phi)) <=
		        m_options.convergedYaw)
			near += w;
	}
	return total > 0 ? near / total : 0;
}

}  // namespace semnav
