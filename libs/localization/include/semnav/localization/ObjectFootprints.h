/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/math/TPoint2D.h>
#include <mrpt/poses/CPose2D.h>
#include <semnav/localization/SemanticObservation.h>

#include <vector>

namespace semnav
{
class LabeledSweep;

/** Object footprints for mapping with localization: posts, bins and other
 * compact objects as points on the ground, scored against the footprints
 * established from earlier sweeps.
 *
 * A sweep sees an object's near faces only, so its surface points (and
 * their centroid) lie short of the object's centre by up to its depth, and
 * matching them against faces seen from other poses pulls the estimate
 * back toward those poses. A footprint is the object's centre instead: the
 * centroid of a compact cluster of obstacle (or blocking object) points,
 * moved away from the robot by pi/4 of the cluster's half-width (the mean
 * depth of the visible half of a cylinder). Only compact clusters that
 * stand on the ground, clear of walls, doors and other clusters, count
 * (wall fragments and pieces of furniture slide with the viewpoint). The
 * map side is a list of landmarks (running means of the footprints of the
 * sweeps inserted so far, at their estimated poses); a landmark is scored
 * once seen from `min_sweeps` sweeps.
 *
 * Options: INI section [ObjectFootprints] (config/localization.ini). */
class ObjectFootprints
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

		/** points: weight of the term in effective points (0: off). */
		double points = 6;
		/** sigma_m, max_distance_m: distance of a footprint to the nearest
		 * established landmark (Gaussian plus a random part, clamped). */
		double sigma = 0.15;
		double maxDistance = 0.5;
		/** gate_m: a footprint is scored only when, at the predicted pose,
		 * a landmark lies this close (new objects are no mismatch). */
		double gate = 1.0;
		/** hit_weight, random_weight: mixture of the Gaussian and a
		 * uniform part. */
		double hitWeight = 0.9;
		double randomWeight = 0.1;
		/** cell_m: obstacle points are clustered on a grid of this cell
		 * (8-connected). */
		double cell = 0.1;
		/** max_width_m: clusters wider than this are no compact object. */
		double maxWidth = 0.4;
		/** min_width_m: clusters narrower than this across the ray are the
		 * edge of something seen side-on (a table's side), not a post. */
		double minWidth = 0.02;
		/** min_height_m: clusters lower than this (above the ground) are
		 * left out (grass bumps). */
		double minHeight = 0.2;
		/** min_points: clusters with fewer points are left out. */
		int minPoints = 8;
		/** max_bottom_m: clusters whose lowest point is higher than this
		 * above the ground stand on nothing (table tops). */
		double maxBottom = 0.5;
		/** clearance_m: clusters with a structure point (wall, door) or
		 * another cluster this close are left out (wall fragments, jambs,
		 * pieces of a larger object). */
		double clearance = 0.3;
		/** max_range_m: farther points are left out. */
		double maxRange = 8.0;
		/** associate_m: a footprint within this of a landmark joins it. */
		double associate = 0.5;
		/** min_sweeps: a landmark is scored once seen from this many
		 * sweeps. */
		int minSweeps = 1;

		bool enabled() const { return points > 0; }
	};

	/** A footprint (robot frame) or a landmark (world frame). */
	struct Footprint
	{
		double x = 0, y = 0;
		/** Estimated radius (half the visible width), m. */
		double radius = 0;
		/** Sweeps it was seen from (landmarks). */
		int sweeps = 1;
	};

	ObjectFootprints() = default;
	explicit ObjectFootprints(const TOptions& o) : m_options(o) {}

	/** The compact objects of a sweep, robot frame. */
	std::vector<Footprint> extract(const LabeledSweep& sweep) const;

	/** Adds a sweep's footprints, seen from `pose`, to the landmarks. */
	void insert(
	    const std::vector<Footprint>& footprints,
	    const mrpt::poses::CPose2D& pose);

	/** The footprints that, seen from (x, y, yaw), lie within `gate_m` of
	 * an established landmark: the fixed subset scored at every
	 * particle. */
	std::vector<SemanticSample> observedPart(
	    double x, double y, double yaw,
	    const std::vector<Footprint>& footprints) const;

	/** Weighted mean log-likelihood of footprints seen from (x, y, yaw)
	 * (0 without established landmarks or footprints). */
	double logLikelihood(
	    double x, double y, double yaw,
	    const std::vector<SemanticSample>& footprints) const;

	/** Landmarks (world frame), established or not. */
	const std::vector<Footprint>& landmarks() const { return m_landmarks; }
	const TOptions& options() const { return m_options; }

private:
	/** Index of the nearest landmark seen from >= minSweeps sweeps (or of
	 * any landmark), -1 when none lies within maxD; d its distance. */
	int nearest(
	    double wx, double wy, bool establishedOnly, double maxD,
	    double& d) const;

	TOptions m_options;
	std::vector<Footprint> m_landmarks;
	/** Sums of the landmarks' world positions (running means). */
	std::vector<mrpt::math::TPoint2D> m_sums;
};

}  // namespace semnav
