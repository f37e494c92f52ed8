/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/OptionTable.h>
#include <semnav/localization/MainDirections.h>
#include <semnav/localization/WallExtractor.h>
#include <semnav/perception/LabeledSweep.h>

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
	std::vector<double> xs, ys;
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
		const WallSegment s =
		    fitWallSegment(xs, ys, m_options.endpointQuantile);
		if (s.residual > m_options.maxResidual ||
		    s.length() < m_options.minLength)
			continue;
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
