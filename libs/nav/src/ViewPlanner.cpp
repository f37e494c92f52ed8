/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/math/wrap2pi.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/poses/CPose2D.h>
#include <semnav/common/OptionTable.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/nav/ViewPlanner.h>
#include <semnav/planning/CnnPlanner.h>
#include <semnav/planning/GoalLayer.h>
#include <semnav/planning/PlanningErrors.h>

#include <algorithm>
#include <cmath>

namespace semnav
{
namespace
{
using O = ViewPlanner::TOptions;
const OptionTable<O>& optionTable()
{
	static const auto t =
	    OptionTable<O>()
	        .flag(
	            "enabled", &O::enabled,
	            "An ambiguous start drives to a place whose view tells the "
	            "hypotheses apart (false: only turn on the spot).")
	        .integer("max_drives", &O::maxDrives, 0, 100, "Drives per start...")
	        .real("budget_m", &O::budget, 0, 1000, "...and metres per start.")
	        .real("max_drive_m", &O::maxDrive, 0.1, 100, "Path of one drive.")
	        .real(
	            "candidate_step_m", &O::candidateStep, 0.05, 5,
	            "Grid of the end points tried...")
	        .real(
	            "min_drive_m", &O::minDrive, 0, 100,
	            "...at least this far from the robot.")
	        .real(
	            "end_clearance_m", &O::endClearance, 0, 5,
	            "The drive ends where the robot could also stand this far "
	            "off (odometry drifts while it drives).")
	        .real("view_range_m", &O::viewRange, 0.5, 80, "Predicted view...")
	        .angle("view_fov_deg", &O::viewFov, 10, 360, "...and its width.")
	        .real(
	            "range_tolerance_m", &O::rangeTolerance, 0.01, 10,
	            "A ray differs between hypotheses by more range or another "
	            "object at its end.")
	        .real(
	            "min_known_fraction", &O::minKnownFraction, 0, 1,
	            "Views with fewer rays ending in observed cells under both "
	            "hypotheses are not compared.")
	        .real(
	            "min_difference", &O::minDifference, 0, 1,
	            "A move needs this share of differing rays...")
	        .real(
	            "cost_per_m", &O::costPerMetre, 0, 10,
	            "...and maximizes difference - cost_per_m x distance.")
	        .real(
	            "drive_speed_m_s", &O::driveSpeed, 0.01, 2,
	            "Speed of the drive (by odometry)...")
	        .angle(
	            "turn_speed_deg_s", &O::turnSpeed, 1, 360,
	            "...and of its turns.");
	return t;
}

constexpr int kRays = 360;  // one per degree, ray k at (k - 180) deg
}  // namespace

SEMNAV_OPTIONS_FROM_TABLE(ViewPlanner::TOptions, optionTable())

ViewPlanner::ViewPlanner(
    const SemanticMap& map, TraversabilityGrid u, const TOptions& options)
    : m_map(map), m_u(std::move(u)), m_options(options)
{
	m_grid = map.occupancyGrid();
	const auto& g = map.geometry();
	for (int cy = 0; cy < g.rows; cy++)
		for (int cx = 0; cx < g.cols; cx++)
			m_grid.setCell(
			    cx, cy,
			    map.at("observations", cx, cy) > 0
			        ? static_cast<float>(1.0 - map.occupancy(cx, cy))
			        : 0.0f);
}

bool ViewPlanner::freeAt(double x, double y) const
{
	int cx, cy;
	if (!m_map.geometry().worldToCell(x, y, cx, cy) ||
	    m_map.at("observations", cx, cy) <= 0)
		return false;
	const auto c = m_u.geometry().cellOf(x, y);
	return c && !m_u.blocked(*c);
}

bool ViewPlanner::clearAt(double x, double y) const
{
	if (!freeAt(x, y)) return false;
	const double r = m_options.endClearance;
	for (int k = 0; k < 8; k++)
		if (!freeAt(
		        x + r * std::cos(k * M_PI / 4), y + r * std::sin(k * M_PI / 4)))
			return false;
	return true;
}

ViewPlanner::View ViewPlanner::view(const mrpt::math::TPose2D& pose) const
{
	mrpt::obs::CObservation2DRangeScan scan;
	scan.aperture = static_cast<float>(2 * M_PI);
	scan.rightToLeft = true;
	scan.maxRange = static_cast<float>(m_options.viewRange);
	m_grid.laserScanSimulator(
	    scan, mrpt::poses::CPose2D(pose), 0.5f, kRays + 1);
	View v;
	v.range.resize(kRays);
	v.what.assign(kRays, 0);
	const auto& g = m_map.geometry();
	for (int k = 0; k < kRays; k++)
	{
		const bool hit = scan.getScanRangeValidity(k);
		const float r = hit ? scan.getScanRange(k) : scan.maxRange;
		v.range[k] = r;
		if (!hit) continue;
		const double a = pose.phi + mrpt::DEG2RAD(double(k - 180));
		const double d = r + 0.5 * g.resolution;
		int cx, cy;
		if (!g.worldToCell(
		        pose.x + d * std::cos(a), pose.y + d * std::sin(a), cx, cy) ||
		    m_map.at("observations", cx, cy) <= 0)
		{
			v.what[k] = -1;
			continue;
		}
		for (int dy = -1; dy <= 1 && !v.what[k]; dy++)
			for (int dx = -1; dx <= 1 && !v.what[k]; dx++)
			{
				if (!g.contains(cy + dy, cx + dx)) continue;
				const int id = m_map.objectId(cx + dx, cy + dy);
				if (id > 0)
					v.what[k] = static_cast<int>(m_map.instance(id).label) + 1;
			}
	}
	return v;
}

double ViewPlanner::difference(
    const View& a, const View& b, double heading) const
{
	int window = 0, known = 0, differ = 0;
	for (int k = 0; k < kRays; k++)
	{
		const double angle = mrpt::DEG2RAD(double(k - 180));
		if (std::abs(mrpt::math::wrapToPi(angle - heading)) >
		    0.5 * m_options.viewFov)
			continue;
		window++;
		if (a.what[k] < 0 || b.what[k] < 0) continue;
		known++;
		if (std::abs(a.range[k] - b.range[k]) > m_options.rangeTolerance ||
		    a.what[k] != b.what[k])
			differ++;
	}
	if (window == 0 || known < m_options.minKnownFraction * window) return 0;
	return double(differ) / double(window);
}

double ViewPlanner::score(
    const std::vector<View>& views, const std::vector<Hypothesis>& h,
    double& heading) const
{
	double best = 0;
	for (int s = 0; s < 8; s++)
	{
		const double psi = mrpt::math::wrapToPi(s * M_PI / 4);
		double sum = 0, weights = 0;
		for (std::size_t i = 0; i < views.size(); i++)
			for (std::size_t j = i + 1; j < views.size(); j++)
			{
				const double w = h[i].weight * h[j].weight;
				sum += w * difference(views[i], views[j], psi);
				weights += w;
			}
		const double v = weights > 0 ? sum / weights : 0;
		if (v > best) best = v, heading = psi;
	}
	return best;
}

std::optional<ViewPlanner::Move> ViewPlanner::plan(
    const std::vector<Hypothesis>& h, double maxLength) const
{
	if (h.size() < 2 || maxLength < m_options.minDrive) return std::nullopt;
	const mrpt::poses::CPose2D best(h[0].pose);
	const mrpt::poses::CPose2D toRobot = -best;
	// Cost from every cell to where the robot stands under the best
	// hypothesis: one diffusion serves every end point.
	GoalLayer here(m_u.geometry());
	DiffusionField field;
	CnnPlanner::TOptions cnnOptions;
	cnnOptions.threads = 1;
	try
	{
		here.addPoint(best.x(), best.y());
		field = CnnPlanner(cnnOptions).computeField(m_u, here);
	}
	catch (const PlanningError&)
	{
		return std::nullopt;
	}
	// The point `p` (world under the best hypothesis) under hypothesis j.
	const auto under = [&](std::size_t j, const mrpt::math::TPoint2D& p)
	{
		double rx, ry, x, y;
		toRobot.composePoint(p.x, p.y, rx, ry);
		mrpt::poses::CPose2D(h[j].pose).composePoint(rx, ry, x, y);
		return mrpt::math::TPoint2D(x, y);
	};
	struct Candidate
	{
		double value, difference, heading;
		CellIndex cell;
	};
	std::vector<Candidate> candidates;
	const auto& g = m_u.geometry();
	const int stride = std::max(
	    1,
	    static_cast<int>(std::lround(m_options.candidateStep / g.resolution)));
	for (int row = 0; row < g.rows; row += stride)
		for (int col = 0; col < g.cols; col += stride)
		{
			const mrpt::math::TPoint2D p(g.centerX(col), g.centerY(row));
			const double d = std::hypot(p.x - best.x(), p.y - best.y());
			if (d < m_options.minDrive || d > maxLength ||
			    !field.reached({row, col}))
				continue;
			std::vector<View> views;
			for (std::size_t j = 0; j < h.size(); j++)
			{
				const mrpt::math::TPoint2D q = under(j, p);
				if (!clearAt(q.x, q.y)) break;
				views.push_back(view({q.x, q.y, h[j].pose.phi}));
			}
			if (views.size() < h.size()) continue;
			double heading = 0;
			const double s = score(views, h, heading);
			if (s < m_options.minDifference) continue;
			candidates.push_back(
			    {s - m_options.costPerMetre * d, s, heading, {row, col}});
		}
	std::sort(
	    candidates.begin(), candidates.end(),
	    [](const Candidate& a, const Candidate& b)
	    { return a.value > b.value; });
	for (const Candidate& c : candidates)
	{
		PlannedPath path;
		try
		{
			path = CnnPlanner::extractPath(field, m_u, here, c.cell);
		}
		catch (const PlanningError&)
		{
			continue;
		}
		if (path.lengthM > maxLength) continue;
		std::reverse(path.points.begin(), path.points.end());
		bool free = true;
		for (std::size_t j = 1; j < h.size() && free; j++)
			for (const auto& p : path.points)
			{
				const mrpt::math::TPoint2D q = under(j, p);
				if (!freeAt(q.x, q.y))
				{
					free = false;
					break;
				}
			}
		if (!free) continue;
		Move m;
		for (const auto& p : path.points)
		{
			double rx, ry;
			toRobot.composePoint(p.x, p.y, rx, ry);
			m.path.push_back({rx, ry});
		}
		m.heading = c.heading;
		m.difference = c.difference;
		m.length = path.lengthM;
		m.end = {
		    path.points.back().x, path.points.back().y,
		    mrpt::math::wrapToPi(best.phi() + c.heading)};
		return m;
	}
	return std::nullopt;
}

}  // namespace semnav
