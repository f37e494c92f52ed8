/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/core/bits_math.h>
#include <semnav/common/ConfigChecks.h>
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

void MainDirections::TEstimateOptions::load(
    const mrpt::config::CConfigFileBase& c, const std::string& s)
{
	tolerance = mrpt::DEG2RAD(readChecked(
	    c, s, "direction_tolerance_deg", mrpt::RAD2DEG(tolerance), 0.1, 45));
	minLength = readChecked(c, s, "direction_min_length_m", minLength, 0, 1000);
	minFraction =
	    readChecked(c, s, "direction_min_fraction", minFraction, 0, 1);
}

void MainDirections::TEstimateOptions::save(
    mrpt::config::CConfigFileBase& c, const std::string& s) const
{
	c.write(s, "direction_tolerance_deg", mrpt::RAD2DEG(tolerance));
	c.write(s, "direction_min_length_m", minLength);
	c.write(s, "direction_min_fraction", minFraction);
}

const std::vector<std::string>& MainDirections::TEstimateOptions::keys()
{
	static const std::vector<std::string> k{
	    "direction_tolerance_deg", "direction_min_length_m",
	    "direction_min_fraction"};
	return k;
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
