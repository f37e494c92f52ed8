/* semnav: semantic navigation from tilting-laser sweeps */
/* CascadeDetector's 3D measurement of a candidate: its object points among
 * a box's pixels (measure), what continues above them (continuingShare)
 * and the object grown around them (growObject). */
#include <semnav/common/Percentile.h>
#include <semnav/detection/BackWall.h>
#include <semnav/detection/CascadeDetector.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <limits>

namespace semnav
{
namespace
{
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

// Flags per pixel of a MeasureGrid: one of the pixels, and not floor or
// surface; a candidate (not too far behind); kept (connected).
constexpr uint8_t kIn = 1, kValid = 2, kCand = 4, kKept = 8;

/** measure()'s pixels: their bounding box padded by one on every side (0
 * on the border, so that neighbours need no bounds checks) with flags per
 * pixel (kIn, and kValid where not floor nor surface). */
class MeasureGrid
{
public:
	MeasureGrid(
	    const cv::Mat& points, const cv::Mat& labels,
	    const std::vector<cv::Point>& pixels, double zFloor, double rangeLo,
	    double rangeHi, std::vector<uint8_t>& state)
	    : m_points(points),
	      m_labels(labels),
	      m_hasLabels(!labels.empty()),
	      m_zFloor(zFloor),
	      m_rangeLo(rangeLo),
	      m_rangeHi(rangeHi),
	      m_state(state)
	{
		int x0 = INT_MAX, y0 = INT_MAX, x1 = -1, y1 = -1;
		for (const auto& px : pixels)
		{
			x0 = std::min(x0, px.x);
			y0 = std::min(y0, px.y);
			x1 = std::max(x1, px.x);
			y1 = std::max(y1, px.y);
		}
		m_region = cv::Rect(x0, y0, x1 - x0 + 1, y1 - y0 + 1);
		pw = m_region.width + 2;
		m_state.assign(std::size_t(pw) * std::size_t(m_region.height + 2), 0);
		for (const auto& px : pixels)
			m_state[padded(px.x, px.y)] =
			    nonFloor(px.x, px.y) ? kIn | kValid : kIn;
	}
	const cv::Vec3f& pointAt(int x, int y) const
	{
		return m_points.ptr<cv::Vec3f>(y)[x];
	}
	double horizontal(int x, int y) const
	{
		const cv::Vec3f& p = pointAt(x, y);
		return std::hypot(double(p[0]), double(p[1]));
	}
	/** Not floor (within floorTolerance of the ground) nor a surface, and
	 * within the range window if any. Ground labels (floor, sidewalk,
	 * grass) are left to the height test: the rules' ground areas can
	 * swallow the top of a low object. */
	bool nonFloor(int x, int y) const
	{
		const cv::Vec3f& p = pointAt(x, y);
		if (!(std::isfinite(p[0]) && p[2] >= m_zFloor)) return false;
		if (m_rangeHi > 0 &&
		    ((m_rangeLo > 0 && compareHypot(p[0], p[1], m_rangeLo) < 0) ||
		     compareHypot(p[0], p[1], m_rangeHi) > 0))
			return false;
		if (!m_hasLabels) return true;
		switch (static_cast<Label>(m_labels.ptr<uint8_t>(y)[x]))
		{
			case Label::Ceiling:
			case Label::Wall:
			case Label::Door:
				return false;
			default:
				return true;
		}
	}
	std::size_t padded(int x, int y) const
	{
		return std::size_t((y - m_region.y + 1) * pw + (x - m_region.x + 1));
	}
	uint8_t& flags(const cv::Point& px) { return m_state[padded(px.x, px.y)]; }
	bool contains(const cv::Point& px) const { return m_region.contains(px); }
	/** The pixel at padded index a. */
	cv::Point pixelAt(int a) const
	{
		return {a % pw - 1 + m_region.x, a / pw - 1 + m_region.y};
	}
	std::vector<uint8_t>& state() { return m_state; }
	/** Row stride of the padded grid. */
	int pw = 0;

private:
	const cv::Mat& m_points;
	const cv::Mat& m_labels;
	const bool m_hasLabels;
	const double m_zFloor, m_rangeLo, m_rangeHi;
	std::vector<uint8_t>& m_state;
	cv::Rect m_region;
};

/** How far the object is: the nearest part (10th percentile of the
 * horizontal distance) of the box's centre (of all valid pixels if the
 * centre has none); false when there is none. */
bool nearestDistance(
    MeasureGrid& g, const std::vector<cv::Point>& pixels,
    const std::vector<cv::Point>& centre, MeasureScratch& sc, double& near)
{
	std::vector<double>& centreD = sc.centreD;
	centreD.clear();
	for (const auto& px : centre)
	{
		const uint8_t f = g.contains(px) ? g.flags(px) : 0;
		if (f & kIn ? f & kValid : g.nonFloor(px.x, px.y))
			centreD.push_back(g.horizontal(px.x, px.y));
	}
	if (centreD.empty())
		for (const auto& px : pixels)
			if (g.flags(px) & kValid)
				centreD.push_back(g.horizontal(px.x, px.y));
	if (centreD.empty()) return false;
	near = percentilesOf(centreD, 0.1, 0.1, sc.select, sc.buckets).first;
	return true;
}

/** Flags as candidates the valid pixels not farther than `far`
 * (horizontally); returns how many. */
std::size_t markCandidates(
    MeasureGrid& g, const std::vector<cv::Point>& pixels, double far)
{
	std::size_t candidates = 0;
	for (const auto& px : pixels)
	{
		uint8_t& f = g.flags(px);
		const cv::Vec3f& p = g.pointAt(px.x, px.y);
		if ((f & kValid) && compareHypot(p[0], p[1], far) <= 0)
		{
			f |= kCand;
			candidates++;
		}
	}
	return candidates;
}

/** Unflags the candidates on or behind a BackWall at least `length` long. */
void dropBackWall(
    MeasureGrid& g, const std::vector<cv::Point>& pixels, double length,
    MeasureScratch& sc)
{
	sc.wallXy.clear();
	sc.wallAt.clear();
	for (const auto& px : pixels)
		if (g.flags(px) & kCand)
		{
			const cv::Vec3f& p = g.pointAt(px.x, px.y);
			sc.wallXy.emplace_back(p[0], p[1]);
			sc.wallAt.push_back(g.padded(px.x, px.y));
		}
	BackWall::Params wp;
	wp.minLength = length;
	if (const auto wall = BackWall::find(sc.wallXy, wp))
		for (std::size_t i = 0; i < sc.wallXy.size(); i++)
			if (wall->distance(sc.wallXy[i]) >= -wp.tolerance)
				g.state()[sc.wallAt[i]] &= uint8_t(~kCand);
}

/** Flags as kept the candidates connected to the centre's: 8-neighbours
 * closer in 3D than a gap growing with the range (the kept set is what the
 * centre reaches, in any visiting order); returns how many. */
std::size_t keepConnected(
    MeasureGrid& g, const std::vector<cv::Point>& centre, MeasureScratch& sc)
{
	std::vector<uint8_t>& state = g.state();
	const int pw = g.pw;
	std::vector<int>& queue = sc.queue;
	queue.clear();
	for (const auto& px : centre)
		if (g.contains(px))
		{
			uint8_t& f = g.flags(px);
			if ((f & (kCand | kKept)) == kCand)
			{
				f |= kKept;
				queue.push_back(int(g.padded(px.x, px.y)));
			}
		}
	const int offsets[8] = {-pw - 1, -pw, -pw + 1, -1, 1, pw - 1, pw, pw + 1};
	for (std::size_t i = 0; i < queue.size(); i++)
	{
		const int a = queue[i];
		const cv::Point pxa = g.pixelAt(a);
		const cv::Vec3f pa = g.pointAt(pxa.x, pxa.y);
		const double gap = connectionGap(pa);
		for (int k = 0; k < 8; k++)
		{
			const int b = a + offsets[k];
			uint8_t& f = state[std::size_t(b)];
			if ((f & (kCand | kKept)) != kCand) continue;
			const cv::Point pxb = g.pixelAt(b);
			const cv::Vec3f d = g.pointAt(pxb.x, pxb.y) - pa;
			if (std::sqrt(d.dot(d)) > gap) continue;
			f |= kKept;
			queue.push_back(b);
		}
	}
	return queue.size();
}

/** The object of the pixels flagged `keep` (about `kept` of them): its
 * points, box, centroid and extents; nothing under minPoints. */
std::optional<CascadeDetector::Measure> objectOf(
    MeasureGrid& g, const std::vector<cv::Point>& pixels, uint8_t keep,
    std::size_t kept, int minPoints, double groundZ, MeasureScratch& sc)
{
	CascadeDetector::Measure m;
	std::vector<double> xs, ys, zs;
	xs.reserve(kept);
	ys.reserve(kept);
	zs.reserve(kept);
	m.pixels.reserve(kept);
	double sx = 0, sy = 0, sz = 0;
	int c0 = INT_MAX, r0 = INT_MAX, c1 = -1, r1 = -1;
	for (const auto& px : pixels)
	{
		if (!(g.flags(px) & keep)) continue;
		const cv::Vec3f& p = g.pointAt(px.x, px.y);
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
}  // namespace

std::optional<CascadeDetector::Measure> CascadeDetector::measure(
    const cv::Mat& points, const cv::Mat& labels,
    const std::vector<cv::Point>& pixels, const std::vector<cv::Point>& centre,
    double groundZ, double floorTolerance, double maxDepth, int minPoints,
    bool connected, double backWallLength, double rangeLo, double rangeHi)
{
	if (pixels.empty()) return std::nullopt;
	MeasureScratch& sc = tlMeasure;
	MeasureGrid g(
	    points, labels, pixels, groundZ + floorTolerance, rangeLo, rangeHi,
	    sc.state);
	double near = 0;
	if (!nearestDistance(g, pixels, centre, sc, near)) return std::nullopt;
	// Candidates: non-floor, non-surface points not too far behind. The
	// object is some of them: too few, and it is too small.
	const double far = near + maxDepth;
	if (static_cast<int>(markCandidates(g, pixels, far)) < minPoints)
		return std::nullopt;
	if (backWallLength > 0) dropBackWall(g, pixels, backWallLength, sc);
	// Object points, for the reservations below.
	std::size_t kept = 0;
	if (connected)
		kept = keepConnected(g, centre, sc);
	else
		for (const auto& px : pixels) kept += (g.flags(px) & kCand) != 0;
	return objectOf(
	    g, pixels, connected ? kKept : kCand, kept, minPoints, groundZ, sc);
}

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

namespace
{
/** The highest object pixel (row) of each column of the measured box; -1
 * where the column has none. */
std::vector<int> columnTops(const CascadeDetector::Measure& m)
{
	std::vector<int> top(std::size_t(std::max(0, m.box.width)), -1);
	for (const auto& p : m.pixels)
	{
		int& t = top[std::size_t(p.x - m.box.x)];
		t = std::max(t, p.y);
	}
	return top;
}
}  // namespace

double CascadeDetector::continuingShare(
    const cv::Mat& points, const cv::Mat& labels, const Measure& m)
{
	const std::vector<int> top = columnTops(m);
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

double CascadeDetector::overheadShare(
    const cv::Mat& points, const cv::Mat& labels, const Measure& m,
    double groundZ)
{
	const std::vector<int> top = columnTops(m);
	// The object's front: its nearest point (horizontally).
	double front = std::numeric_limits<double>::infinity();
	for (const auto& p : m.pixels)
	{
		const cv::Vec3f a = points.at<cv::Vec3f>(p.y, p.x);
		if (std::isfinite(a[0]))
			front = std::min(front, std::hypot(double(a[0]), double(a[1])));
	}
	const double zTop = groundZ + m.top;
	const double reach = m.width / 2 + kOverheadReach / 2;
	int columns = 0, covered = 0;
	for (std::size_t i = 0; i < top.size(); i++)
	{
		if (top[i] < 0) continue;
		columns++;
		const int col = m.box.x + int(i);
		for (int r = top[i] + 1; r < points.rows; r++)
		{
			const cv::Vec3f b = points.at<cv::Vec3f>(r, col);
			if (!std::isfinite(b[0]) || b[2] < zTop + 0.03 ||
			    b[2] > zTop + kOverheadReach)
				continue;
			if (!labels.empty() && static_cast<Label>(labels.at<uint8_t>(
			                           r, col)) == Label::Ceiling)
				continue;
			const double h = std::hypot(double(b[0]), double(b[1]));
			const double d =
			    std::hypot(b[0] - m.centroid.x, b[1] - m.centroid.y);
			if (h < front - 0.02 && d <= reach)
			{
				covered++;
				break;
			}
		}
	}
	return columns ? double(covered) / columns : 0;
}

std::optional<double> CascadeDetector::flatFaceShare(
    const cv::Mat& points, const Measure& m, double groundZ)
{
	// The front of the top band in each column: the points within 2 cm of
	// the column's nearest (a vertical face puts every tilt line's point
	// of a column at one place; the median of them is the laser's noise
	// over their count).
	const double zLow = groundZ + m.top - kFlatFaceBand;
	std::vector<std::vector<cv::Vec2d>> columns(
	    std::size_t(std::max(0, m.box.width)));
	for (const auto& p : m.pixels)
	{
		const cv::Vec3f& a = points.at<cv::Vec3f>(p);
		if (std::isfinite(a[0]) && a[2] >= zLow)
			columns[std::size_t(p.x - m.box.x)].emplace_back(a[0], a[1]);
	}
	std::vector<cv::Vec2d> front;
	std::vector<double> xs, ys;
	for (auto& col : columns)
	{
		if (col.empty()) continue;
		double nearest = std::numeric_limits<double>::infinity();
		for (const auto& q : col) nearest = std::min(nearest, cv::norm(q));
		xs.clear();
		ys.clear();
		for (const auto& q : col)
			if (cv::norm(q) <= nearest + 0.02)
			{
				xs.push_back(q[0]);
				ys.push_back(q[1]);
			}
		front.emplace_back(percentile(xs, 0.5), percentile(ys, 0.5));
	}
	// The directions of the front between points kFlatFaceBaseline apart
	// (not across a gap), folded by 90 deg (4 x the angle): a box's faces
	// become one direction; the mean of the folded unit vectors points at
	// the one that holds the most.
	std::vector<double> folded;
	double sc = 0, ss = 0;
	for (std::size_t k = 0; k < front.size(); k++)
		for (std::size_t j = k + 1; j < front.size(); j++)
		{
			const cv::Vec2d d = front[j] - front[k];
			const double len = cv::norm(d);
			if (len < kFlatFaceBaseline) continue;
			if (len <= 2 * kFlatFaceBaseline)
			{
				const double f = 4 * std::atan2(d[1], d[0]);
				folded.push_back(f);
				sc += std::cos(f);
				ss += std::sin(f);
			}
			break;
		}
	if (int(folded.size()) < kFlatFaceMinSegments) return std::nullopt;
	const double mode = std::atan2(ss, sc);
	const double tol = 4 * kFlatFaceToleranceDeg * M_PI / 180;
	std::size_t on = 0;
	for (const double f : folded)
		on += std::abs(std::remainder(f - mode, 2 * M_PI)) <= tol;
	return double(on) / double(folded.size());
}

}  // namespace semnav
