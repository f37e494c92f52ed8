/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/common/OptionTable.h>
#include <semnav/localization/WallSegment.h>

#include <optional>
#include <string>
#include <vector>

namespace semnav
{
/** Dominant wall direction of a set of segments, modulo 90 deg (the
 * "main directions" of a structured environment, paper sec. 2.3). */
class MainDirections
{
public:
	/** Estimation parameters: keys direction_tolerance_deg,
	 * direction_min_length_m, direction_min_fraction of the section of the
	 * class that estimates (WallExtractor, WallMap). */
	struct TEstimateOptions
	{
		/** Inlier tolerance (rad). */
		double tolerance = 5.0 * M_PI / 180;
		/** Minimum inlier length (m) and fraction of the total length. */
		double minLength = 1.5;
		double minFraction = 0.5;

		/** The keys, for OptionTable::embed() in the estimating class's
		 * table. */
		static const OptionTable<TEstimateOptions>& optionTable();
	};

	/** estimate() with the options' parameters. */
	static std::optional<double> estimate(
	    const std::vector<WallSegment>& segments, const TEstimateOptions& o)
	{
		return estimate(segments, o.tolerance, o.minLength, o.minFraction);
	}

	/** Wraps an angle to [-pi/4, pi/4) (period 90 deg). */
	static double wrapQuarter(double a);

	/** Length-weighted mean of the segments' directions modulo 90 deg (mean
	 * of 4 * angle on the circle), refined on the segments within
	 * `inlierTolerance` (rad) of the first estimate. Empty when the inliers
	 * are shorter than `minInlierLength` (m) or hold less than
	 * `minInlierFraction` of the total length. */
	static std::optional<double> estimate(
	    const std::vector<WallSegment>& segments, double inlierTolerance,
	    double minInlierLength, double minInlierFraction);

	/** Heading correction that aligns a sweep's dominant direction
	 * `observed` (robot frame) with the map's `mapDirection` (world) for a
	 * robot heading `yaw`: the result is wrapQuarter(map - observed - yaw),
	 * to be added to yaw. */
	static double correction(double yaw, double observed, double mapDirection)
	{
		return wrapQuarter(mapDirection - observed - yaw);
	}
};

}  // namespace semnav
