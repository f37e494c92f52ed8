/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/OptionTable.h>
#include <semnav/localization/MainDirections.h>
#include <semnav/localization/WallExtractor.h>
#include <semnav/perception/LabeledSweep.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace semnav
{
namespace
{
using O = WallExtractor::TOptions;
const OptionTable<O>& optionTable()
{
	static const auto t =
	    OptionTable<O>()
	        .integer(
	            "min_points", &O::minPoints, 3, 1000000,
	            "Wall regions with fewer points are skipped.")
	        .real(
	            "min_length_m", &O::minLength, 0, 100,
	            "Fitted segments shorter than this are dropped.")
	        .real(
	            "max_residual_m", &O::maxResidual, 0.001, 1,
	            "Segments whose points spread more around the line are "
	            "dropped.")
	        .real(
	            "max_normal_z", &O::maxNormalZ, 0, 1,
	            "|normal z| above this is not a vertical surface.")
	        .real(
	            "endpoint_quantile", &O::endpointQuantile, 0, 0.25,
	            "Endpoints at this quantile of the points along the line "
	            "(and 1 - it).")
	        .real(
	            "sample_spacing_m", &O::sampleSpacing, 0.01, 10,
	            "Spacing of the likelihood samples along the segments.")
	        .integer(
	            "max_samples", &O::maxSamples, 1, 100000,
	            "At most this many likelihood samples per sweep.")
	        .embed(
	            &O::directions,
	            MainDirections::TEstimateOptions::optionTable());
	return t;
}
}  // namespace

SEMNAV_OPTIONS_FROM_TABLE(WallExtractor::TOptions, optionTable())

WallObservation WallExtractor::extract(const LabeledSweep& ls) const
{
	WallObservation obs;
	obs.sweepIndex = ls.sweepIndex;
	std::vector<double> xs, ys, along;
	for (const auto& reg : ls.regions)
	{
		if (reg.label != Label::Wall ||
		    reg.pixels < static_cast<std::size_t>(m_options.minPoints) ||
		    std::abs(reg.meanNormal.z) > m_options.maxNormalZ)
			continue;
		xs.clear();
		ys.clear();
		const cv::Rect& b = reg.imageBox;
		for (int r = b.y; r < b.y + b.height; r++)
		{
			const int* ids = ls.regionIds.ptr<int>(r);
			const cv::Vec3f* pts = ls.points.ptr<cv::Vec3f>(r);
			for (int c = b.x; c < b.x + b.width; c++)
			{
				if (ids[c] != reg.id || !std::isfinite(pts[c][0])) continue;
				xs.push_back(pts[c][0]);
				ys.push_back(pts[c][1]);
			}
		}
		const std::size_t n = xs.size();
		if (n < static_cast<std::size_t>(m_options.minPoints)) continue;
		// Total least squares: principal axis of the (x, y) scatter.
		double mx = 0, my = 0;
		for (std::size_t i = 0; i < n; i++) mx += xs[i], my += ys[i];
		mx /= n, my /= n;
		double sxx = 0, sxy = 0, syy = 0;
		for (std::size_t i = 0; i < n; i++)
		{
			const double dx = xs[i] - mx, dy = ys[i] - my;
			sxx += dx * dx, sxy += dx * dy, syy += dy * dy;
		}
		Eigen::Matrix2d cov;
		cov << sxx / n, sxy / n, sxy / n, syy / n;
		Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(cov);
		const double lMin = std::max(0.0, es.eigenvalues()(0));
		const double lMax = std::max(1e-12, es.eigenvalues()(1));
		const Eigen::Vector2d d = es.eigenvectors().col(1);
		const double residual = std::sqrt(lMin);
		if (residual > m_options.maxResidual) continue;
		along.resize(n);
		for (std::size_t i = 0; i < n; i++)
			along[i] = (xs[i] - mx) * d.x() + (ys[i] - my) * d.y();
		const auto q = [&](double f)
		{
			const std::size_t k = std::min(
			    n - 1, static_cast<std::size_t>(std::lround(f * (n - 1))));
			std::nth_element(along.begin(), along.begin() + k, along.end());
			return along[k];
		};
		const double t0 = q(m_options.endpointQuantile);
		const double t1 = q(1 - m_options.endpointQuantile);
		if (t1 - t0 < m_options.minLength) continue;
		WallSegment s;
		s.p0 = {mx + t0 * d.x(), my + t0 * d.y()};
		s.p1 = {mx + t1 * d.x(), my + t1 * d.y()};
		s.points = n;
		s.residual = residual;
		// Line fit: var(offset) = s^2 / n, var(angle) = s^2 / (n var_along).
		s.sigmaOffset = residual / std::sqrt(double(n));
		s.sigmaAngle = residual / std::sqrt(double(n) * lMax);
		obs.segments.push_back(s);
	}
	finish(obs);
	return obs;
}

void WallExtractor::finish(WallObservation& obs) const
{
	obs.samples.clear();
	double total = 0;
	for (const auto& s : obs.segments) total += s.length();
	if (total <= 0)
	{
		obs.dominantDirection.reset();
		return;
	}
	const double spacing = std::max(
	    m_options.sampleSpacing, total / std::max(1, m_options.maxSamples));
	// Evenly along the concatenated segments (offset half a step).
	double carry = spacing / 2;
	for (const auto& s : obs.segments)
	{
		const double len = s.length();
		const auto dir = (s.p1 - s.p0) * (1.0 / std::max(len, 1e-9));
		for (double t = carry; t <= len; t += spacing)
			obs.samples.push_back(s.p0 + dir * t);
		carry = std::fmod(carry - len, spacing);
		if (carry < 0) carry += spacing;
	}
	obs.dominantDirection =
	    MainDirections::estimate(obs.segments, m_options.directions);
}

}  // namespace semnav
