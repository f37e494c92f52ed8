/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/Percentile.h>
#include <semnav/detection/BackWall.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace semnav
{
namespace
{
/** Hypotheses are scored on at most this many points (a fixed stride). */
constexpr std::size_t kScoredPoints = 400;

std::optional<BackWall::Line> lineThrough(cv::Point2d a, cv::Point2d b)
{
	const cv::Point2d d = b - a;
	const double len = std::hypot(d.x, d.y);
	if (len < 0.2) return std::nullopt;
	BackWall::Line l;
	l.normal = cv::Point2d(-d.y / len, d.x / len);
	l.offset = l.normal.dot(a);
	if (l.offset < 0)
	{
		l.normal = -l.normal;
		l.offset = -l.offset;
	}
	return l;
}
}  // namespace

std::optional<BackWall::Line> BackWall::find(
    const std::vector<cv::Point2d>& xy, const Params& params)
{
	const std::size_t n = xy.size();
	if (n < 20) return std::nullopt;
	// No line of minLength fits in a smaller box.
	double x0 = xy[0].x, x1 = x0, y0 = xy[0].y, y1 = y0;
	for (const auto& p : xy)
	{
		x0 = std::min(x0, p.x);
		x1 = std::max(x1, p.x);
		y0 = std::min(y0, p.y);
		y1 = std::max(y1, p.y);
	}
	if (std::hypot(x1 - x0, y1 - y0) < params.minLength) return std::nullopt;
	const std::size_t stride = std::max<std::size_t>(1, n / kScoredPoints);
	const std::size_t scored = (n + stride - 1) / stride;
	const double maxBehindScored = params.maxBehind * double(scored);
	// The line with the most points on it and few behind.
	std::minstd_rand rng(12345);
	std::uniform_int_distribution<std::size_t> pick(0, n - 1);
	std::optional<Line> best;
	std::size_t bestOn = 0;
	for (int h = 0; h < params.hypotheses; h++)
	{
		const auto l = lineThrough(xy[pick(rng)], xy[pick(rng)]);
		if (!l) continue;
		std::size_t on = 0, behind = 0;
		for (std::size_t i = 0; i < n; i += stride)
		{
			const double s = l->distance(xy[i]);
			on += std::abs(s) <= params.tolerance;
			behind += s > params.tolerance;
			if (double(behind) > maxBehindScored) break;
		}
		if (double(behind) > maxBehindScored) continue;
		if (on > bestOn)
		{
			bestOn = on;
			best = l;
		}
	}
	if (!best) return std::nullopt;
	// Checked on every point: few behind, enough in front, long, and
	// reaching past what is in front.
	const cv::Point2d along(-best->normal.y, best->normal.x);
	std::vector<double> onT, frontT;
	std::size_t behind = 0;
	for (const auto& p : xy)
	{
		const double s = best->distance(p);
		if (s > params.tolerance)
			behind++;
		else if (s >= -params.tolerance)
			onT.push_back(along.dot(p));
		else
			frontT.push_back(along.dot(p));
	}
	if (double(behind) > params.maxBehind * double(n) ||
	    double(frontT.size()) < params.minInFront * double(n) ||
	    onT.size() < 10)
		return std::nullopt;
	const auto [w0, w1] = percentiles(onT, 0.05, 0.95);
	const auto [f0, f1] = percentiles(frontT, 0.05, 0.95);
	if (w1 - w0 < params.minLength) return std::nullopt;
	if (std::max(0.0, f0 - w0) + std::max(0.0, w1 - f1) < params.minOverhang)
		return std::nullopt;
	return best;
}

}  // namespace semnav
