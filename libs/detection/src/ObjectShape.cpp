/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/Label.h>
#include <semnav/common/Percentile.h>
#include <semnav/detection/ObjectShape.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <functional>
#include <opencv2/core.hpp>
#include <tuple>
#include <utility>

namespace semnav
{
namespace
{
/** The 5th and 95th percentiles of a non-empty `v` (percentilesOf, a
 * scratch per thread). */
std::pair<double, double> ends(const std::vector<double>& v)
{
	thread_local std::vector<double> select[2];
	thread_local std::vector<uint8_t> buckets;
	return percentilesOf(v, 0.05, 0.95, select, buckets);
}

/** 95th minus 5th percentile; 0 for fewer than 3 values. */
float spread(const std::vector<double>& v)
{
	if (v.size() < 3) return 0;
	const auto [lo, hi] = ends(v);
	return float(hi - lo);
}
/** The object-frame grids (ObjectShape::kGridFeatures) into `out`: cells
 * split the height from the ground to the highest point and the depth and
 * side extents (at least 5 cm each). */
void describeGrids(
    const std::vector<double>& lat, const std::vector<double>& dep,
    const std::vector<double>& h, const std::vector<cv::Vec3d>& n, float* out)
{
	constexpr int g = ObjectShape::kGridSide;
	float* shareDepth = out;
	float* upDepth = out + g * g;
	float* shareSide = out + 2 * g * g;
	const auto [d0, d1] = std::minmax_element(dep.begin(), dep.end());
	const auto [l0, l1] = std::minmax_element(lat.begin(), lat.end());
	const double top = std::max(*std::max_element(h.begin(), h.end()), 0.05);
	const double depthSpan = std::max(*d1 - *d0, 0.05);
	const double sideSpan = std::max(*l1 - *l0, 0.05);
	const auto cell = [](double v) { return std::clamp(int(v * g), 0, g - 1); };
	std::array<int, g * g> inDepthCell{};
	const float share = 1.0f / float(h.size());
	for (std::size_t i = 0; i < h.size(); i++)
	{
		const int row = cell(h[i] / top) * g;
		const int d = row + cell((dep[i] - *d0) / depthSpan);
		shareDepth[d] += share;
		shareSide[row + cell((lat[i] - *l0) / sideSpan)] += share;
		upDepth[d] += float(std::abs(n[i][2]));
		inDepthCell[std::size_t(d)]++;
	}
	for (int k = 0; k < g * g; k++)
		upDepth[k] = inDepthCell[std::size_t(k)]
		                 ? upDepth[k] / float(inDepthCell[std::size_t(k)])
		                 : -1.0f;
}
/** Steps along the sweep's columns into out[0..3]: in a column (one beam
 * angle, the tilt climbing) a flight's risers are runs of points at one
 * horizontal range, each a tread's run farther and a rise higher than the
 * one below. Mean steps per column (of those with 3 points), the share
 * of columns with two, and the median run and rise of the steps. */
void describeSteps(
    const cv::Mat& points, const std::vector<cv::Point>& object, double groundZ,
    float* out)
{
	// (height, horizontal range) of the points, bucketed by column, each
	// column from the ground up.
	thread_local std::vector<cv::Vec2f> byColumn;
	thread_local std::vector<int> columnStart;
	thread_local std::vector<double> runs, rises;
	runs.clear();
	rises.clear();
	int c0 = INT_MAX, c1 = -1;
	for (const auto& px : object)
	{
		c0 = std::min(c0, px.x);
		c1 = std::max(c1, px.x);
	}
	if (c1 < 0) return;
	columnStart.assign(std::size_t(c1 - c0 + 2), 0);
	for (const auto& px : object)
		if (std::isfinite(points.at<cv::Vec3f>(px)[0]))
			columnStart[std::size_t(px.x - c0 + 1)]++;
	for (std::size_t k = 1; k < columnStart.size(); k++)
		columnStart[k] += columnStart[k - 1];
	byColumn.resize(std::size_t(columnStart.back()));
	for (const auto& px : object)
	{
		const auto& q = points.at<cv::Vec3f>(px);
		if (!std::isfinite(q[0])) continue;
		byColumn[std::size_t(columnStart[std::size_t(px.x - c0)]++)] =
		    cv::Vec2f(q[2] - float(groundZ), std::hypot(q[0], q[1]));
	}
	// columnStart[k] is now the end of column k (the start of k + 1).
	constexpr float kFaceGap = 0.05f;
	int columns = 0, climbing = 0, steps = 0;
	for (std::size_t col = 0, i = 0; col + 1 < columnStart.size(); col++)
	{
		const std::size_t j = std::size_t(columnStart[col]);
		std::sort(
		    byColumn.begin() + long(i), byColumn.begin() + long(j),
		    [](const cv::Vec2f& a, const cv::Vec2f& b) { return a[0] < b[0]; });
		if (j - i >= 3)
		{
			columns++;
			// Faces: points whose ranges follow each other within kFaceGap.
			int inColumn = 0;
			float faceBottom = byColumn[i][0], faceTop = faceBottom;
			float faceRange = byColumn[i][1];
			int facePoints = 1;
			bool havePrevious = false;
			float prevBottom = 0, prevRange = 0;
			const auto close = [&]
			{
				if (facePoints >= 2 && faceTop - faceBottom >= 0.03f)
				{
					if (havePrevious)
					{
						const float run = faceRange - prevRange;
						const float rise = faceBottom - prevBottom;
						if (run >= 0.12f && run <= 0.65f && rise >= 0.06f &&
						    rise <= 0.35f)
						{
							inColumn++;
							runs.push_back(run);
							rises.push_back(rise);
						}
					}
					havePrevious = true;
					prevBottom = faceBottom;
					prevRange = faceRange;
				}
			};
			for (std::size_t k = i + 1; k < j; k++)
			{
				const cv::Vec2f& v = byColumn[k];
				if (std::abs(v[1] - byColumn[k - 1][1]) <= kFaceGap)
				{
					faceTop = v[0];
					faceRange = v[1];
					facePoints++;
					continue;
				}
				close();
				faceBottom = faceTop = v[0];
				faceRange = v[1];
				facePoints = 1;
			}
			close();
			steps += inColumn;
			climbing += inColumn >= 2;
		}
		i = j;
	}
	if (columns == 0) return;
	out[0] = float(steps) / float(columns);
	out[1] = float(climbing) / float(columns);
	if (!runs.empty())
	{
		out[2] = float(percentile(runs, 0.5));
		out[3] = float(percentile(rises, 0.5));
	}
}

/** An object's points in its own frame: `along` the line of sight to its
 * centroid, `across` it, heights above the ground. */
struct ObjectFrame
{
	std::vector<cv::Vec3d> p;
	std::vector<cv::Vec3d> n;  ///< normals, zero where none
	cv::Vec3d c{0, 0, 0};      ///< centroid
	double count = 0, bearing = 0;
	cv::Vec2d along, across;
	std::vector<double> lat, dep, h;
	float width = 0, depth = 0;
	double bottom = 0, top = 0;
};

/** The object's valid points in their frame; false when there are none. */
bool objectFrame(
    const cv::Mat& points, const cv::Mat& normals, const cv::Mat& normalMask,
    const std::vector<cv::Point>& object, double groundZ, ObjectFrame& o)
{
	std::vector<cv::Vec3d>&p = o.p, &n = o.n;
	p.reserve(object.size());
	n.reserve(object.size());
	cv::Vec3d& c = o.c;
	for (const auto& px : object)
	{
		const auto& q = points.at<cv::Vec3f>(px);
		if (!std::isfinite(q[0])) continue;
		p.emplace_back(q[0], q[1], q[2]);
		c += p.back();
		n.push_back(
		    normalMask.at<uint8_t>(px) ? cv::Vec3d(normals.at<cv::Vec3f>(px))
		                               : cv::Vec3d(0, 0, 0));
	}
	if (p.empty()) return false;
	o.count = double(p.size());
	c /= o.count;
	o.bearing = std::atan2(c[1], c[0]);
	o.along = cv::Vec2d(std::cos(o.bearing), std::sin(o.bearing));
	o.across = cv::Vec2d(-o.along[1], o.along[0]);
	o.lat.resize(p.size());
	o.dep.resize(p.size());
	o.h.resize(p.size());
	for (std::size_t i = 0; i < p.size(); i++)
	{
		o.lat[i] = o.across[0] * p[i][0] + o.across[1] * p[i][1];
		o.dep[i] = o.along[0] * p[i][0] + o.along[1] * p[i][1];
		o.h[i] = p[i][2] - groundZ;
	}
	o.width = spread(o.lat);
	o.depth = spread(o.dep);
	std::tie(o.bottom, o.top) = ends(o.h);
	return true;
}

/** Size and height profile: f[0..14]. */
void describeSize(const ObjectFrame& o, float* f)
{
	const double count = o.count, top = o.top;
	const float width = o.width;
	f[0] = float(std::hypot(o.c[0], o.c[1]));
	f[1] = float(std::abs(o.bearing));
	f[2] = float(std::log(count));
	f[3] = width;
	f[4] = o.depth;
	f[5] = float(top);
	f[6] = float(o.bottom);
	// Height profile, relative to the top.
	const double scale = std::max(top, 0.05);
	std::array<std::vector<double>, 3> thirds;
	for (std::size_t i = 0; i < o.p.size(); i++)
	{
		const double r = std::clamp(o.h[i] / scale, 0.0, 0.999);
		f[7 + int(r * 5)] += float(1 / count);
		thirds[std::size_t(r * 3)].push_back(o.lat[i]);
	}
	for (int k = 0; k < 3; k++)
		f[12 + k] = spread(thirds[k]) / std::max(width, 0.01f);
}

/** Surfaces: facing up, facing sideways and how the side normals turn
 * (f[15..18], f[29]); the top's up-facing share and depth (f[24..25]).
 * The up-facing points into `upPoints`. */
void describeSurfaces(
    const ObjectFrame& o, float* f, std::vector<std::size_t>& upPoints)
{
	const std::vector<cv::Vec3d>& n = o.n;
	const cv::Vec2d &along = o.along, &across = o.across;
	double withNormal = 0, up = 0, side = 0, sc = 0, ss = 0, oblique = 0;
	std::array<double, 12> sideBins{};
	double topPoints = 0, topUp = 0;
	std::vector<double> topDep;
	for (std::size_t i = 0; i < o.p.size(); i++)
	{
		const bool atTop = o.h[i] > o.top - 0.08;
		if (atTop)
		{
			topPoints++;
			topDep.push_back(o.dep[i]);
		}
		if (n[i] == cv::Vec3d(0, 0, 0)) continue;
		withNormal++;
		if (n[i][2] > 0.8)
		{
			up++;
			upPoints.push_back(i);
			topUp += atTop;
		}
		if (std::abs(n[i][2]) >= 0.3) continue;
		side++;
		const double toward = -(along[0] * n[i][0] + along[1] * n[i][1]);
		const double sideways = across[0] * n[i][0] + across[1] * n[i][1];
		const double a = std::atan2(sideways, toward);
		sc += std::cos(a);
		ss += std::sin(a);
		sideBins[std::size_t(
		    std::clamp(int((a + M_PI) / (M_PI / 6)), 0, 11))]++;
		oblique += std::abs(std::sin(a));
	}
	if (withNormal > 0)
	{
		f[15] = float(up / withNormal);
		f[16] = float(side / withNormal);
	}
	if (side > 0)
	{
		f[17] = float(1 - std::hypot(sc, ss) / side);
		f[18] = float(oblique / side);
		// Flat faces put their normals into one or two 30 deg bins, a
		// cylinder spreads them.
		std::sort(sideBins.begin(), sideBins.end(), std::greater<>());
		f[29] = float((sideBins[0] + sideBins[1]) / side);
	}
	if (topPoints > 0)
	{
		f[24] = float(topUp / topPoints);
		f[25] = spread(topDep);
	}
}

/** Front curvature (f[19]): depth = a + b lat + k lat^2 (least squares), k
 * times the width (a convex front facing the sensor has k > 0). */
void describeCurvature(const ObjectFrame& o, float* f)
{
	if (o.p.size() < 6 || !(o.width > 0.02f)) return;
	double m = 0;
	for (double v : o.lat) m += v;
	m /= o.count;
	cv::Matx33d A = cv::Matx33d::zeros();
	cv::Vec3d b(0, 0, 0);
	for (std::size_t i = 0; i < o.p.size(); i++)
	{
		const double x = o.lat[i] - m;
		const cv::Vec3d row(1, x, x * x);
		A += row * row.t();
		b += row * o.dep[i];
	}
	cv::Vec3d k;
	if (cv::solve(A, b, k, cv::DECOMP_CHOLESKY)) f[19] = float(k[2] * o.width);
}

/** Spread of the points (f[20..21]): the middle and least principal axes
 * against the largest. */
void describeSpread(const ObjectFrame& o, float* f)
{
	cv::Matx33d cov = cv::Matx33d::zeros();
	for (const auto& q : o.p)
	{
		const cv::Vec3d d = q - o.c;
		cov += d * d.t();
	}
	cv::Vec3d ev;
	cv::eigen(cv::Mat(cov * (1 / o.count)), ev);
	if (ev[0] > 1e-12)
	{
		f[20] = float(ev[1] / ev[0]);
		f[21] = float(ev[2] / ev[0]);
	}
}

/** Surroundings (f[22..23]): walls around it and how much of its box it
 * fills. */
void describeSurroundings(
    const cv::Mat& points, const cv::Mat& labels,
    const std::vector<cv::Point>& surroundings, double count, float* f)
{
	double valid = 0, wall = 0;
	for (const auto& px : surroundings)
	{
		if (!std::isfinite(points.at<cv::Vec3f>(px)[0])) continue;
		valid++;
		if (!labels.empty() &&
		    static_cast<Label>(labels.at<uint8_t>(px)) == Label::Wall)
			wall++;
	}
	if (valid > 0)
	{
		f[22] = float(wall / valid);
		f[23] = float(count / valid);
	}
}

/** Surfaces facing up (f[26..28]): at how many heights (5 cm levels holding
 * 3 % of them: a table has one, a flight of stairs one per step), over what
 * span of its height, and how they climb across or along the line of sight
 * (the correlation of height with position, the larger). */
void describeUpLevels(
    const ObjectFrame& o, const std::vector<std::size_t>& upPoints, float* f)
{
	if (upPoints.size() < 3) return;
	const std::vector<double>&h = o.h, &lat = o.lat, &dep = o.dep;
	std::vector<int> levels(64, 0);
	std::vector<double> zs;
	double mz = 0, ml = 0, md = 0;
	for (std::size_t i : upPoints)
	{
		levels[std::size_t(std::clamp(int(h[i] / 0.05), 0, 63))]++;
		zs.push_back(h[i]);
		mz += h[i];
		ml += lat[i];
		md += dep[i];
	}
	const double m = double(upPoints.size());
	int filled = 0;
	for (int l : levels) filled += l >= 0.03 * m;
	f[26] = float(filled);
	f[27] = spread(zs) / float(std::max(o.top, 0.05));
	mz /= m;
	ml /= m;
	md /= m;
	double zz = 0, ll = 0, dd = 0, zl = 0, zd = 0;
	for (std::size_t i : upPoints)
	{
		const double a = h[i] - mz, b = lat[i] - ml, d = dep[i] - md;
		zz += a * a;
		ll += b * b;
		dd += d * d;
		zl += a * b;
		zd += a * d;
	}
	const auto corr = [&](double xy, double yy)
	{ return zz > 0 && yy > 0 ? std::abs(xy) / std::sqrt(zz * yy) : 0.0; };
	f[28] = float(std::max(corr(zl, ll), corr(zd, dd)));
}
}  // namespace

const std::array<std::string, ObjectShape::kFeatures>& ObjectShape::names()
{
	static const std::array<std::string, kFeatures> n = []
	{
		const std::array<const char*, kBaseFeatures> base{
		    "range",          "bearing",
		    "log_points",     "width",
		    "depth",          "top",
		    "bottom",         "height_0_20",
		    "height_20_40",   "height_40_60",
		    "height_60_80",   "height_80_100",
		    "width_lower",    "width_middle",
		    "width_upper",    "facing_up",
		    "facing_side",    "side_turn",
		    "side_oblique",   "front_curvature",
		    "pca_middle",     "pca_least",
		    "wall_around",    "box_fill",
		    "top_facing_up",  "top_depth",
		    "up_levels",      "up_height_spread",
		    "up_slope",       "side_two_faces",
		    "cascade_support"};
		std::array<std::string, kFeatures> all;
		std::copy(base.begin(), base.end(), all.begin());
		int i = kBaseFeatures;
		for (const char* grid : {"share_hd", "up_hd", "share_hs"})
			for (int r = 0; r < kGridSide; r++)
				for (int c = 0; c < kGridSide; c++)
					all[std::size_t(i++)] = std::string(grid) + "_" +
					                        std::to_string(r) + "_" +
					                        std::to_string(c);
		for (const char* step :
		     {"steps_per_column", "climbing_columns", "step_run", "step_rise"})
			all[std::size_t(i++)] = step;
		return all;
	}();
	return n;
}

std::vector<int> ObjectShape::columnsOf(int count)
{
	for (const bool grids : {false, true})
		for (const bool steps : {false, true})
		{
			if (count != featureCount(grids, steps)) continue;
			std::vector<int> columns;
			for (int i = 0; i < kBaseFeatures; i++) columns.push_back(i);
			if (grids)
				for (int i = 0; i < kGridFeatures; i++)
					columns.push_back(kBaseFeatures + i);
			if (steps)
				for (int i = 0; i < kStepFeatures; i++)
					columns.push_back(kStepsAt + i);
			return columns;
		}
	return {};
}

ObjectShape::Features ObjectShape::describe(
    const cv::Mat& points, const cv::Mat& normals, const cv::Mat& normalMask,
    const cv::Mat& labels, const std::vector<cv::Point>& object,
    const std::vector<cv::Point>& surroundings, double groundZ, bool steps)
{
	Features f{};
	ObjectFrame o;
	if (!objectFrame(points, normals, normalMask, object, groundZ, o)) return f;
	describeSize(o, f.data());
	std::vector<std::size_t> upPoints;
	describeSurfaces(o, f.data(), upPoints);
	describeCurvature(o, f.data());
	describeSpread(o, f.data());
	describeSurroundings(points, labels, surroundings, o.count, f.data());
	describeUpLevels(o, upPoints, f.data());
	describeGrids(o.lat, o.dep, o.h, o.n, f.data() + kBaseFeatures);
	if (steps) describeSteps(points, object, groundZ, f.data() + kStepsAt);
	return f;
}

}  // namespace semnav
