/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/OptionTable.h>
#include <semnav/localization/MainDirections.h>
#include <semnav/localization/WallMap.h>
#include <semnav/map/SemanticMap.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>

namespace semnav
{
namespace
{
using O = WallMap::TOptions;
const OptionTable<O>& optionTable()
{
	static const auto t =
	    OptionTable<O>()
	        .real(
	            "resolution_m", &O::resolution, 0.005, 1,
	            "Cell size of the likelihood field over the map's walls.")
	        .real(
	            "sigma_m", &O::sigma, 0.005, 5,
	            "Std dev of a wall sample's distance to a map wall.")
	        .real(
	            "max_distance_m", &O::maxDistance, 0.01, 50,
	            "Distances are clamped to this.")
	        .real(
	            "hit_weight", &O::hitWeight, 0, 1,
	            "Mixture weight of the wall likelihood.")
	        .real(
	            "random_weight", &O::randomWeight, 1e-6, 1,
	            "Mixture weight of a random return.")
	        .real(
	            "unknown_weight", &O::unknownWeight, 1e-6, 1,
	            "Likelihood of a sample in a never-observed cell (new "
	            "walls are not mismatches).")
	        .real(
	            "unknown_extension_m", &O::unknownExtension, 0, 100,
	            "Segments go on this far into never-observed cells.")
	        .real("margin_m", &O::margin, 0, 100, "Room around the walls.")
	        .embed(
	            &O::directions,
	            MainDirections::TEstimateOptions::optionTable());
	return t;
}
}  // namespace

SEMNAV_OPTIONS_FROM_TABLE(WallMap::TOptions, optionTable())

void WallMap::addSegments(const std::vector<WallSegment>& worldSegments)
{
	m_segments.insert(
	    m_segments.end(), worldSegments.begin(), worldSegments.end());
}

void WallMap::addObservation(
    const std::vector<WallSegment>& robotSegments,
    const mrpt::poses::CPose2D& pose)
{
	for (const auto& s : robotSegments)
		m_segments.push_back(s.transformed(pose));
}

GridGeometry WallMap::fieldGeometry(const SemanticMap* observed) const
{
	double x0 = std::numeric_limits<double>::max(), y0 = x0;
	double x1 = -x0, y1 = -x0;
	for (const auto& s : m_segments)
		for (const auto& p : {s.p0, s.p1})
		{
			x0 = std::min(x0, p.x), y0 = std::min(y0, p.y);
			x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
		}
	const double res = m_options.resolution, m = m_options.margin;
	if (observed)
	{
		// The field covers what the map observed (beyond it: unknown).
		const auto& og = observed->geometry();
		x0 = std::min(x0, og.originX + m), y0 = std::min(y0, og.originY + m);
		x1 = std::max(x1, og.maxX() - m), y1 = std::max(y1, og.maxY() - m);
	}
	return GridGeometry(
	    res, x0 - m, y0 - m,
	    static_cast<int>(std::ceil((x1 - x0 + 2 * m) / res)),
	    static_cast<int>(std::ceil((y1 - y0 + 2 * m) / res)));
}

CellRect WallMap::drawSegments(std::size_t from)
{
	const double res = m_geometry.resolution;
	const auto toPx = [&](const mrpt::math::TPoint2D& p)
	{
		return cv::Point(
		    static_cast<int>((p.x - m_geometry.originX) / res),
		    static_cast<int>((p.y - m_geometry.originY) / res));
	};
	CellRect drawn;
	const auto draw = [&](cv::Mat& mask, const mrpt::math::TPoint2D& a,
	                      const mrpt::math::TPoint2D& b)
	{
		const cv::Point pa = toPx(a), pb = toPx(b);
		cv::line(mask, pa, pb, cv::Scalar(1), 1, cv::LINE_8);
		drawn.add(std::min(pa.y, pb.y), std::min(pa.x, pb.x));
		drawn.add(std::max(pa.y, pb.y), std::max(pa.x, pb.x));
	};
	cv::Mat lines(m_geometry.rows, m_geometry.cols, CV_8U, m_lines.data());
	cv::Mat ext;
	if (!m_extension.empty())
		ext = cv::Mat(
		    m_geometry.rows, m_geometry.cols, CV_8U, m_extension.data());
	const double e = m_options.unknownExtension;
	for (std::size_t k = from; k < m_segments.size(); k++)
	{
		const WallSegment& s = m_segments[k];
		draw(lines, s.p0, s.p1);
		// A wall seen up to the edge of the view goes on into the unseen
		// cells: extend the segments there, else a new view of the wall is
		// pulled back onto the known part (a bias along the wall).
		const double len = s.length();
		if (m_extension.empty() || e <= 0 || len <= 0) continue;
		const auto d = (s.p1 - s.p0) * (e / len);
		draw(ext, s.p0 - d, s.p0);
		draw(ext, s.p1, s.p1 + d);
	}
	m_drawn = m_segments.size();
	return drawn.clipped(m_geometry);
}

CellRect WallMap::markUnknown(
    const SemanticMap& observed, const CellRect& cells)
{
	const auto& obs = observed.get("observations");
	const auto& og = observed.geometry();
	CellRect flipped;
	for (int r = cells.row0; r < cells.row1; r++)
		for (int c = cells.col0; c < cells.col1; c++)
		{
			int cx, cy;
			const uint8_t unknown =
			    og.worldToCell(
			        m_geometry.centerX(c), m_geometry.centerY(r), cx, cy) &&
			            obs[og.index(cy, cx)] > 0
			        ? 0
			        : 1;
			auto& u = m_unknownMask[m_geometry.index(r, c)];
			if (u != unknown) flipped.add(r, c);
			u = unknown;
		}
	return flipped;
}

void WallMap::maskWalls(const CellRect& cells)
{
	for (int r = cells.row0; r < cells.row1; r++)
		for (int c = cells.col0; c < cells.col1; c++)
		{
			const std::size_t i = m_geometry.index(r, c);
			m_wallMask[i] = m_lines[i] || (!m_extension.empty() &&
			                               m_extension[i] && m_unknownMask[i]);
		}
}

void WallMap::rebuild(const SemanticMap* observed)
{
	m_main.reset();
	m_field.clear();
	m_source = nullptr;
	m_fromSemanticMap = false;
	if (m_segments.empty()) return;
	m_geometry = fieldGeometry(observed);
	const std::size_t n = m_geometry.cellCount();
	m_lines.assign(n, 0);
	m_extension.assign(observed ? n : 0, 0);
	m_unknownMask.assign(observed ? n : 0, 1);
	drawSegments(0);
	const CellRect all = CellRect::all(m_geometry);
	if (observed) markUnknown(*observed, all);
	m_wallMask.assign(n, 0);
	maskWalls(all);
	if (observed)
	{
		m_source = observed;
		m_version = observed->version();
	}
	buildField(observed != nullptr);
	m_main = MainDirections::estimate(m_segments, m_options.directions);
}

void WallMap::buildFromSemanticMap(
    const SemanticMap& map, bool unobservedUnknown)
{
	m_segments.clear();
	m_main.reset();
	m_lines.clear();
	m_extension.clear();
	m_geometry = map.geometry();
	m_wallMask.assign(m_geometry.cellCount(), 0);
	m_unknownMask.assign(unobservedUnknown ? m_wallMask.size() : 0, 0);
	const CellRect all = CellRect::all(m_geometry);
	readSemanticMap(map, all);
	buildField(unobservedUnknown);
	houghSegments();
	m_source = &map;
	m_version = map.version();
	m_fromSemanticMap = true;
}

float WallMap::mixtureLogLikelihood(
    double d, double sigma, double maxDistance, double hit, double random)
{
	d = std::min(d, maxDistance);
	return static_cast<float>(
	    std::log(hit * std::exp(-d * d / (2 * sigma * sigma)) + random));
}

void WallMap::buildField(bool withUnknown)
{
	const double res = m_geometry.resolution;
	m_unknown = static_cast<float>(std::log(m_options.unknownWeight));
	m_field.resize(m_geometry.cellCount());
	m_distance.resize(m_field.size());
	m_x0 = m_geometry.originX;
	m_y0 = m_geometry.originY;
	m_invRes = 1.0 / res;
	m_nx = m_geometry.cols;
	m_ny = m_geometry.rows;
	m_floor = value(m_options.maxDistance);
	m_outside = withUnknown ? std::max(m_floor, m_unknown) : m_floor;
	if (!withUnknown) m_unknownMask.clear();
	m_ceiling = value(0);
	computeField(CellRect::all(m_geometry));
}

float WallMap::value(double d) const
{
	return mixtureLogLikelihood(
	    d, m_options.sigma, m_options.maxDistance, m_options.hitWeight,
	    m_options.randomWeight);
}

int WallMap::reach() const
{
	// Cells farther from every wall than the clamp distance, or than the
	// inlier distance, all score alike.
	const double far = std::max(m_options.maxDistance, 2 * m_options.sigma);
	return static_cast<int>(std::ceil(far / m_geometry.resolution)) + 1;
}

void WallMap::computeField(const CellRect& cells)
{
	// A cell's distance matters up to reach() cells only: the distance
	// transform of the window around `cells` is the whole map's there.
	const int n = reach();
	const CellRect out = cells.dilated(n).clipped(m_geometry);
	const CellRect in = out.dilated(n).clipped(m_geometry);
	if (out.empty()) return;
	const int w = in.col1 - in.col0, h = in.row1 - in.row0;
	cv::Mat src(h, w, CV_8U);
	for (int r = 0; r < h; r++)
	{
		const uint8_t* wall =
		    &m_wallMask[m_geometry.index(in.row0 + r, in.col0)];
		uint8_t* row = src.ptr<uint8_t>(r);
		for (int c = 0; c < w; c++) row[c] = wall[c] ? 0 : 255;
	}
	cv::Mat dist;
	cv::distanceTransform(src, dist, cv::DIST_L2, cv::DIST_MASK_PRECISE);
	const double res = m_geometry.resolution;
	const float clamp = static_cast<float>((n - 1) * res);
	for (int r = out.row0; r < out.row1; r++)
	{
		const float* d = dist.ptr<float>(r - in.row0) - in.col0;
		for (int c = out.col0; c < out.col1; c++)
		{
			const std::size_t i = m_geometry.index(r, c);
			m_distance[i] = std::min(static_cast<float>(d[c] * res), clamp);
			m_field[i] = value(m_distance[i]);
			if (!m_unknownMask.empty() && m_unknownMask[i])
				m_field[i] = std::max(m_field[i], m_unknown);
		}
	}
}

double WallMap::logLikelihood(
    double x, double y, double yaw,
    const std::vector<mrpt::math::TPoint2D>& pts) const
{
	const double c = std::cos(yaw), s = std::sin(yaw);
	double sum = 0;
	for (const auto& p : pts)
		sum += logLikelihood(x + c * p.x - s * p.y, y + s * p.x + c * p.y);
	return sum;
}

double WallMap::knownLogLikelihood(
    double x, double y, double yaw,
    const std::vector<mrpt::math::TPoint2D>& pts, std::size_t& known) const
{
	const double c = std::cos(yaw), s = std::sin(yaw);
	double sum = 0;
	known = 0;
	for (const auto& p : pts)
	{
		const double wx = x + c * p.x - s * p.y, wy = y + s * p.x + c * p.y;
		const int cx = static_cast<int>((wx - m_x0) * m_invRes);
		const int cy = static_cast<int>((wy - m_y0) * m_invRes);
		if (wx < m_x0 || wy < m_y0 || cx >= m_nx || cy >= m_ny) continue;
		const std::size_t i = static_cast<std::size_t>(cy) * m_nx + cx;
		if (!m_unknownMask.empty() && m_unknownMask[i]) continue;
		sum += m_field[i];
		known++;
	}
	return sum;
}

double WallMap::inlierFraction(
    const mrpt::poses::CPose2D& pose,
    const std::vector<mrpt::math::TPoint2D>& pts) const
{
	if (pts.empty() || m_field.empty()) return pts.empty() ? 1.0 : 0.0;
	std::size_t in = 0;
	const double lim = 2 * m_options.sigma;
	for (const auto& p : pts)
	{
		const auto w = WallSegment::compose(pose, p);
		const int cx = static_cast<int>((w.x - m_x0) * m_invRes);
		const int cy = static_cast<int>((w.y - m_y0) * m_invRes);
		if (w.x < m_x0 || w.y < m_y0 || cx >= m_nx || cy >= m_ny) continue;
		if (m_distance[static_cast<std::size_t>(cy) * m_nx + cx] <= lim) in++;
	}
	return double(in) / pts.size();
}

}  // namespace semnav
