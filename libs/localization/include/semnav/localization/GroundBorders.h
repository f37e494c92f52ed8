/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/core/bits_math.h>
#include <semnav/localization/MainDirections.h>
#include <semnav/localization/WallSegment.h>

#include <optional>
#include <string>
#include <vector>

namespace semnav
{
class LabeledSweep;

/** Ground borders as heading evidence: the straight edges between sidewalk
 * and grass near the robot, as 2D segments in the robot frame, and their
 * dominant direction modulo 90 deg (MainDirections), for the main-direction
 * heading correction of a sweep whose walls give no direction (outdoors at a
 * building's corner the walls are behind or edge-on; the paths run along
 * the walls).
 *
 * Border points are the ground pixels labelled sidewalk with a grass pixel
 * among their 4 neighbours in the sweep image (or grass next to sidewalk)
 * between `min_range_m` and `max_range_m` (far ground types are poor),
 * thinned to one per `cell_m`. Lines are found by MRPT's RANSAC
 * (mrpt::math::ransac_detect_2D_lines, run on a generator seeded apart so
 * the particle filter's random stream is not touched); each line's inliers
 * are refitted (total least squares) and cut at gaps, the longest run kept
 * when at least `min_length_m` long with `min_points` points.
 *
 * Options: INI section [GroundBorders] (config/localization.ini). */
class GroundBorders
{
public:
	struct TOptions : public mrpt::config::CLoadableOptions
	{
		void loadFromConfigFile(
		    const mrpt::config::CConfigFileBase& c,
		    const std::string& section) override;
		void saveToConfigFile(
		    mrpt::config::CConfigFileBase& c,
		    const std::string& section) const override;

		/** enabled: mapping uses the borders' direction when the sweep's
		 * walls give none. */
		bool enabled = true;
		/** min_range_m, max_range_m: border points by their distance to the
		 * robot. */
		double minRange = 0.5;
		double maxRange = 4.5;
		/** cell_m: one border point per cell of this size. */
		double cell = 0.05;
		/** line_threshold_m: RANSAC inlier distance to a line. */
		double lineThreshold = 0.06;
		/** min_points: a border segment has at least this many points. */
		int minPoints = 25;
		/** min_length_m: shorter border segments are dropped. */
		double minLength = 1.0;
		/** max_gap_m: a line's inliers are cut where they are farther
		 * apart than this; the longest run is the segment. */
		double maxGap = 0.4;
		/** max_correction_deg: the direction is used only when it moves the
		 * predicted heading by at most this (a diagonal path is not a
		 * main direction). */
		double maxCorrection = mrpt::DEG2RAD(15.0);
		/** Keys direction_tolerance_deg, direction_min_length_m,
		 * direction_min_fraction: MainDirections over the segments. */
		MainDirections::TEstimateOptions directions;
	};

	GroundBorders() = default;
	explicit GroundBorders(const TOptions& o) : m_options(o) {}

	/** The sweep's border points (robot frame, thinned); empty indoors. */
	std::vector<mrpt::math::TPoint2D> points(const LabeledSweep& s) const;
	/** Straight border segments through `pts` (robot frame). */
	std::vector<WallSegment> segments(
	    const std::vector<mrpt::math::TPoint2D>& pts) const;
	/** The segments' dominant direction modulo 90 deg (rad, in
	 * [-pi/4, pi/4), robot frame), when they agree on one. */
	std::optional<double> direction(const LabeledSweep& s) const;

	const TOptions& options() const { return m_options; }

private:
	TOptions m_options;
};

}  // namespace semnav
