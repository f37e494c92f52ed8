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

void WallMap::rebuild(const SemanticMap* observed)
{
	m_main.reset();
	m_field.clear();
	if (m_segments.empty()) return;
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
	m_geometry = GridGeometry(
	    res, x0 - m, y0 - m,
	    static_cast<int>(std::ceil((x1 - x0 + 2 * m) / res)),
	    static_cast<int>(std::ceil((y1 - y0 + 2 * m) / res)));
	cv::Mat mask(m_geometry.rows, m_geometry.cols, CV_8U, cv::Scalar(0));
	const auto toPx = [&](const mrpt::math::TPoint2D& p)
	{
		return cv::Point(
		    static_cast<int>((p.x - m_geometry.originX) / res),
		    static_cast<int>((p.y - m_geometry.originY) / res));
	};
	for (const auto& s : m_segments)
		cv::line(mask, toPx(s.p0), toPx(s.p1), cv::Scalar(1), 1, cv::LINE_8);
	std::vector<uint8_t> unknown;
	if (observed)
	{
		unknown.assign(m_geometry.cellCount(), 1);
		const auto& obs = observed->get("observations");
		const auto& og = observed->geometry();
		for (int r = 0; r < m_geometry.rows; r++)
			for (int c = 0; c < m_geometry.cols; c++)
			{
				int cx, cy;
				if (og.worldToCell(
				        m_geometry.centerX(c), m_geometry.centerY(r), cx, cy) &&
				    obs[og.index(cy, cx)] > 0)
					unknown[m_geometry.index(r, c)] = 0;
			}
		// A wall seen up to the edge of the view goes on into the unseen
		// cells: extend the segments there, else a new view of the wall is
		// pulled back onto the known part (a bias along the wall).
		const double e = m_options.unknownExtension;
		if (e > 0)
		{
			cv::Mat ext(m_geometry.rows, m_geometry.cols, CV_8U, cv::Scalar(0));
			for (const auto& s : m_segments)
			{
				const double len = s.length();
				if (len <= 0) continue;
				const auto d = (s.p1 - s.p0) * (e / len);
				cv::line(ext, toPx(s.p0 - d), toPx(s.p0), cv::Scalar(1));
				cv::line(ext, toPx(s.p1), toPx(s.p1 + d), cv::Scalar(1));
			}
			for (std::size_t i = 0; i < unknown.size(); i++)
				if (ext.data[i] && unknown[i]) mask.data[i] = 1;
		}
	}
	buildField(
	    std::vector<uint8_t>(mask.datastart, mask.dataend),
	    observed ? &unknown : nullptr);
	m_main = MainDirections::estimate(m_segments, m_options.directions);
}

void WallMap::buildFromSemanticMap(
    const SemanticMap& map, bool unobservedUnknown)
{
	m_segments.clear();
	m_main.reset();
	m_geometry = map.geometry();
	std::vector<uint8_t> wall(m_geometry.cellCount(), 0);
	std::vector<uint8_t> unknown(unobservedUnknown ? wall.size() : 0, 0);
	for (int cy = 0; cy < m_geometry.rows; cy++)
		for (int cx = 0; cx < m_geometry.cols; cx++)
		{
			if (map.labels(cx, cy).contains(Label::Wall))
				wall[m_geometry.index(cy, cx)] = 1;
			if (unobservedUnknown && !(map.at("observations", cx, cy) > 0))
				unknown[m_geometry.index(cy, cx)] = 1;
		}
	buildField(wall, unobservedUnknown ? &unknown : nullptr);
	// Segments of the wall cells: probabilistic Hough transform.
	cv::Mat mask(m_geometry.rows, m_geometry.cols, CV_8U, wall.data());
	std::vector<cv::Vec4i> lines;
	const double res = m_geometry.resolution;
	cv::HoughLinesP(mask, lines, 1, CV_PI / 360, 15, 0.5 / res, 2);
	for (const auto& l : lines)
	{
		WallSegment s;
		s.p0 = {m_geometry.centerX(l[0]), m_geometry.centerY(l[1])};
		s.p1 = {m_geometry.centerX(l[2]), m_geometry.centerY(l[3])};
		m_segments.push_back(s);
	}
	m_main = MainDirections::estimate(m_segments, m_options.directions);
}

float WallMap::mixtureLogLikelihood(
    double d, double sigma, double maxDistance, double hit, double random)
{
	d = std::min(d, maxDistance);
	return static_cast<float>(
	    std::log(hit * std::exp(-d * d / (2 * sigma * sigma)) + random));
}

void WallMap::buildField(
    const std::vector<uint8_t>& wallMask,
    const std::vector<uint8_t>* unknownMask)
{
	const int nx = m_geometry.cols, ny = m_geometry.rows;
	cv::Mat src(ny, nx, CV_8U);
	for (std::size_t i = 0; i < wallMask.size(); i++)
		src.data[i] = wallMask[i] ? 0 : 255;
	cv::Mat dist;
	cv::distanceTransform(src, dist, cv::DIST_L2, cv::DIST_MASK_PRECISE);
	const double res = m_geometry.resolution;
	m_unknown = static_cast<float>(std::log(m_options.unknownWeight));
	const auto value = [&](double d)
	{
		return mixtureLogLikelihood(
		    d, m_options.sigma, m_options.maxDistance, m_options.hitWeight,
		    m_options.randomWeight);
	};
	m_field.resize(static_cast<std::size_t>(nx) * ny);
	m_distance.resize(m_field.size());
	for (int r = 0; r < ny; r++)
	{
		const float* d = dist.ptr<float>(r);
		for (int c = 0; c < nx; c++)
		{
			const std::size_t i = static_cast<std::size_t>(r) * nx + c;
			m_distance[i] = static_cast<float>(d[c] * res);
			m_field[i] = value(m_distance[i]);
			if (unknownMask && (*unknownMask)[i])
				m_field[i] = std::max(m_field[i], m_unknown);
		}
	}
	m_x0 = m_geometry.originX;
	m_y0 = m_geometry.originY;
	m_invRes = 1.0 / res;
	m_nx = nx;
	m_ny = ny;
	m_floor = value(m_options.maxDistance);
	m_outside = unknownMask ? std::max(m_floor, m_unknown) : m_floor;
	m_unknownMask = unknownMask ? *unknownMask : std::vector<uint8_t>();
	m_ceiling = value(0);
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
