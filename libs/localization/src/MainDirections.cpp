/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/OptionTable.h>
#include <semnav/localization/MainDirections.h>

#include <cmath>

namespace semnav
{
double MainDirections::wrapQuarter(double a)
{
	const double q = M_PI / 2;
	a = std::fmod(a + M_PI / 4, q);
	if (a < 0) a += q;
	return a - M_PI / 4;
}

const OptionTable<MainDirections::TEstimateOptions>&
MainDirections::TEstimateOptions::optionTable()
{
	using O = TEstimateOptions;
	static const auto t =
	    OptionTable<O>()
	        .angle(
	            "direction_tolerance_deg", &O::tolerance, 0.1, 45,
	            "Walls within this of the main direction are inliers.")
	        .real(
	            "direction_min_length_m", &O::minLength, 0, 1000,
	            "Inliers must be at least this long in total...")
	        .real(
	            "direction_min_fraction", &O::minFraction, 0, 1,
	            "...and this fraction of all walls' length.");
	return t;
}

std::optional<double> MainDirections::estimate(
    const std::vector<WallSegment>& segments, double inlierTolerance,
    double minInlierLength, double minInlierFraction)
{
	// Mean of 4 * angle: directions 90 deg apart coincide.
	auto mean = [&](const std::optional<double>& around, double& inlierLen)
	{
		double s = 0, c = 0;
		inlierLen = 0;
		for (const auto& seg : segments)
		{
			const double a = seg.angle();
			if (around && std::abs(wrapQuarter(a - *around)) > inlierTolerance)
				continue;
			const double w = seg.length();
			s += w * std::sin(4 * a);
			c += w * std::cos(4 * a);
			inlierLen += w;
		}
		return wrapQuarter(std::atan2(s, c) / 4);
	};
	double total = 0, inliers = 0;
	for (const auto& seg : segments) total += seg.length();
	if (total <= 0) return std::nullopt;
	double first = mean(std::nullopt, total);
	// Two refinements on the inliers.
	for (int i = 0; i < 2; i++) first = mean(first, inliers);
	if (inliers < minInlierLength || inliers < minInlierFraction * total)
		return std::nullopt;
	return first;
}

}  // namespace semnav
