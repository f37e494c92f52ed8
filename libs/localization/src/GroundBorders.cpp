/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/math/TLine2D.h>
#include <mrpt/math/ransac.h>
#include <mrpt/random/RandomGenerators.h>
#include <semnav/common/OptionTable.h>
#include <semnav/localization/GroundBorders.h>
#include <semnav/perception/LabeledSweep.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>

namespace semnav
{
namespace
{
using O = GroundBorders::TOptions;
const OptionTable<O>& optionTable()
{
	static const auto t =
	    OptionTable<O>()
	        .flag(
	            "enabled", &O::enabled,
	            "Mapping: a sweep whose walls give no main direction takes "
	            "that of its sidewalk / grass borders.")
	        .real(
	            "min_range_m", &O::minRange, 0, 100,
	            "Border points nearer than this are left out...")
	        .real(
	            "max_range_m", &O::maxRange, 0.5, 100,
	            "...and farther than this (far ground types are poor).")
	        .real(
	            "cell_m", &O::cell, 0.005, 1,
	            "One border point per cell of this size.")
	        .real(
	            "line_threshold_m", &O::lineThreshold, 0.005, 1,
	            "RANSAC inlier distance to a border line.")
	        .integer(
	            "min_points", &O::minPoints, 3, 100000,
	            "A border segment has at least this many points...")
	        .real(
	            "min_length_m", &O::minLength, 0, 100,
	            "...and is at least this long.")
	        .real(
	            "max_gap_m", &O::maxGap, 0.01, 100,
	            "A line's points are cut at gaps wider than this (the "
	            "longest run is kept).")
	        .angle(
	            "max_correction_deg", &O::maxCorrection, 0, 45,
	            "The borders' direction is used only when it moves the "
	            "predicted heading by at most this.")
	        .embed(
	            &O::directions, MainDirections::TEstimateOptions::optionTable())
	        .check(
	            [](const O& o) { return o.minRange < o.maxRange; },
	            "min_range_m must be below max_range_m");
	return t;
}

bool isBorderPixel(const LabeledSweep& s, int r, int c)
{
	const Label l = s.label(r, c);
	if (l != Label::Sidewalk && l != Label::Grass) return false;
	const Label other = l == Label::Sidewalk ? Label::Grass : Label::Sidewalk;
	const int dr[4] = {-1, 1, 0, 0}, dc[4] = {0, 0, -1, 1};
	for (int k = 0; k < 4; k++)
	{
		const int rr = r + dr[k], cc = c + dc[k];
		if (rr < 0 || cc < 0 || rr >= s.labels.rows || cc >= s.labels.cols)
			continue;
		if (s.label(rr, cc) == other) return true;
	}
	return false;
}

/** The longest run of `along` (sorted) without a gap wider than maxGap:
 * [first, last) indices. */
std::pair<std::size_t, std::size_t> longestRun(
    const std::vector<double>& along, double maxGap)
{
	std::pair<std::size_t, std::size_t> best{0, 0};
	std::size_t start = 0;
	for (std::size_t i = 1; i <= along.size(); i++)
	{
		if (i < along.size() && along[i] - along[i - 1] <= maxGap) continue;
		if (along[i - 1] - along[start] >
		    (best.second > best.first
		         ? along[best.second - 1] - along[best.first]
		         : -1.0))
			best = {start, i};
		start = i;
	}
	return best;
}

/** The segment through pts (fitWallSegment, extreme points as ends), or
 * nothing when shorter than minLength or with fewer than minPoints points. */
std::optional<WallSegment> fitSegment(
    const std::vector<mrpt::math::TPoint2D>& pts, const O& o)
{
	if (pts.size() < static_cast<std::size_t>(o.minPoints)) return std::nullopt;
	std::vector<double> xs, ys;
	for (const auto& p : pts) xs.push_back(p.x), ys.push_back(p.y);
	const WallSegment s = fitWallSegment(xs, ys, 0);
	if (s.length() < o.minLength) return std::nullopt;
	return s;
}

using Model = mrpt::math::CMatrixDouble;
using Data = mrpt::math::CMatrixDouble;

/** RANSAC line model through two points: (a, b, c) with a x + b y + c = 0,
 * (a, b) a unit normal. */
void fitLine(
    const Data& d, const std::vector<std::size_t>& idx, std::vector<Model>& out)
{
	out.clear();
	const double x0 = d(0, idx[0]), y0 = d(1, idx[0]);
	const double x1 = d(0, idx[1]), y1 = d(1, idx[1]);
	const double len = std::hypot(x1 - x0, y1 - y0);
	if (len <= 0) return;
	Model m(1, 3);
	m(0, 0) = -(y1 - y0) / len;
	m(0, 1) = (x1 - x0) / len;
	m(0, 2) = -(m(0, 0) * x0 + m(0, 1) * y0);
	out.push_back(m);
}

void lineInliers(
    const Data& d, const std::vector<Model>& models, double threshold,
    unsigned int& best, std::vector<std::size_t>& inliers)
{
	best = 0;
	inliers.clear();
	if (models.empty()) return;
	const Model& m = models[0];
	for (std::size_t i = 0; i < static_cast<std::size_t>(d.cols()); i++)
		if (std::abs(m(0, 0) * d(0, i) + m(0, 1) * d(1, i) + m(0, 2)) <=
		    threshold)
			inliers.push_back(i);
}

bool degenerateLine(const Data& d, const std::vector<std::size_t>& idx)
{
	return d(0, idx[0]) == d(0, idx[1]) && d(1, idx[0]) == d(1, idx[1]);
}

/** Lines through the points, one after the other on the points the
 * previous ones left (MRPT's RANSAC, as ransac_detect_2D_lines, quiet). */
std::vector<mrpt::math::TLine2D> detectLines(
    const std::vector<mrpt::math::TPoint2D>& pts, const O& o)
{
	std::vector<mrpt::math::TLine2D> out;
	std::vector<mrpt::math::TPoint2D> left = pts;
	mrpt::math::RANSAC_Template<double> ransac;
	ransac.setMinLoggingLevel(mrpt::system::LVL_ERROR);
	const auto minPoints = static_cast<std::size_t>(o.minPoints);
	while (left.size() >= minPoints)
	{
		Data d(2, left.size());
		for (std::size_t i = 0; i < left.size(); i++)
			d(0, i) = left[i].x, d(1, i) = left[i].y;
		std::vector<std::size_t> inliers;
		Model m;
		if (!ransac.execute(
		        d, fitLine, lineInliers, degenerateLine, o.lineThreshold, 2,
		        inliers, m) ||
		    inliers.size() < minPoints || m.cols() != 3)
			break;
		out.emplace_back(m(0, 0), m(0, 1), m(0, 2));
		std::vector<bool> used(left.size(), false);
		for (auto i : inliers) used[i] = true;
		std::vector<mrpt::math::TPoint2D> rest;
		for (std::size_t i = 0; i < left.size(); i++)
			if (!used[i]) rest.push_back(left[i]);
		left.swap(rest);
	}
	return out;
}
}  // namespace

SEMNAV_OPTIONS_FROM_TABLE(GroundBorders::TOptions, optionTable())

std::vector<mrpt::math::TPoint2D> GroundBorders::points(
    const LabeledSweep& s) const
{
	std::vector<mrpt::math::TPoint2D> out;
	if (s.indoor || s.labels.empty()) return out;
	std::set<std::pair<long, long>> cells;
	const double r0 = m_options.minRange * m_options.minRange;
	const double r1 = m_options.maxRange * m_options.maxRange;
	for (int r = 0; r < s.labels.rows; r++)
		for (int c = 0; c < s.labels.cols; c++)
		{
			if (!isBorderPixel(s, r, c)) continue;
			const auto& p = s.points.at<cv::Vec3f>(r, c);
			if (!std::isfinite(p[0])) continue;
			const double d2 = double(p[0]) * p[0] + double(p[1]) * p[1];
			if (d2 < r0 || d2 > r1) continue;
			if (cells
			        .insert(
			            {std::lround(p[0] / m_options.cell),
			             std::lround(p[1] / m_options.cell)})
			        .second)
				out.push_back({p[0], p[1]});
		}
	return out;
}

std::vector<WallSegment> GroundBorders::segments(
    const std::vector<mrpt::math::TPoint2D>& pts) const
{
	std::vector<WallSegment> out;
	if (pts.size() < static_cast<std::size_t>(m_options.minPoints)) return out;
	std::vector<mrpt::math::TLine2D> lines;
	{
		// RANSAC draws from MRPT's global generator, which the particle
		// filter uses: run it on its own fixed seed and put the filter's
		// state back.
		auto& rng = mrpt::random::getRandomGenerator();
		const mrpt::random::CRandomGenerator saved = rng;
		rng = mrpt::random::CRandomGenerator(1);
		lines = detectLines(pts, m_options);
		rng = saved;
	}
	for (const auto& line : lines)
	{
		// The line's inliers among all border points, in order along it.
		const double nx = line.coefs[0], ny = line.coefs[1];
		const double norm = std::hypot(nx, ny);
		if (norm <= 0) continue;
		std::vector<std::pair<double, mrpt::math::TPoint2D>> on;
		for (const auto& p : pts)
			if (std::abs(nx * p.x + ny * p.y + line.coefs[2]) / norm <=
			    m_options.lineThreshold)
				on.push_back({(-ny * p.x + nx * p.y) / norm, p});
		std::sort(
		    on.begin(), on.end(),
		    [](const auto& a, const auto& b) { return a.first < b.first; });
		std::vector<double> along;
		for (const auto& e : on) along.push_back(e.first);
		const auto [i0, i1] = longestRun(along, m_options.maxGap);
		std::vector<mrpt::math::TPoint2D> run;
		for (std::size_t i = i0; i < i1; i++) run.push_back(on[i].second);
		if (auto s = fitSegment(run, m_options)) out.push_back(*s);
	}
	return out;
}

std::optional<double> GroundBorders::direction(const LabeledSweep& s) const
{
	const auto segs = segments(points(s));
	if (segs.empty()) return std::nullopt;
	return MainDirections::estimate(segs, m_options.directions);
}

}  // namespace semnav
