/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/maps/COccupancyGridMap2D.h>
#include <mrpt/math/TPoint2D.h>
#include <mrpt/math/TPose2D.h>
#include <semnav/planning/TraversabilityGrid.h>

#include <optional>
#include <string>
#include <vector>

namespace semnav
{
class SemanticMap;

/** Active disambiguation: where to drive and look when the sweeps fit
 * several poses alike (a room and its turned twin).
 *
 * Each hypothesis is a pose the robot may stand at. A move is a relative
 * motion (a path and a final heading in the robot's frame): under each
 * hypothesis it ends somewhere else in the map. The planner predicts the
 * view from each such end pose (MRPT's laserScanSimulator on the map's
 * occupancy, every never-observed cell opaque; the object instance seen at
 * each ray's end) and picks the move whose views differ most between the
 * hypotheses, per metre driven. Paths are planned with the CNN planner on
 * the map under the best hypothesis and must be free (not blocked, observed)
 * under every hypothesis, so the move is safe whichever is true.
 *
 * Options: INI section [ViewPlanner] (config/navigation.ini). */
class ViewPlanner
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

		/** enabled: drive to look when a start stays ambiguous; false:
		 * only turn on the spot. */
		bool enabled = true;
		/** max_drives, budget_m: drives and metres per start. */
		int maxDrives = 3;
		double budget = 12.0;
		/** max_drive_m: path length of one drive. */
		double maxDrive = 3.0;
		/** candidate_step_m: grid of the end points tried. */
		double candidateStep = 0.3;
		/** min_drive_m: end points closer than this are not tried (the
		 * robot has looked around where it stands). */
		double minDrive = 0.5;
		/** end_clearance_m: the end point must be free this far around it
		 * under every hypothesis (the odometry drifts on the way). */
		double endClearance = 0.3;
		/** view_range_m, view_fov_deg: the predicted view. */
		double viewRange = 8.0;
		double viewFov = mrpt::DEG2RAD(180.0);
		/** range_tolerance_m: a ray differs when its ranges under two
		 * hypotheses differ by more, or it ends on different objects. */
		double rangeTolerance = 0.3;
		/** min_known_fraction: rays that end in observed cells under both
		 * hypotheses, below which a view is not compared. */
		double minKnownFraction = 0.3;
		/** min_difference: a move is taken only if this share of its rays
		 * differ... */
		double minDifference = 0.15;
		/** cost_per_m: ...and it maximizes difference - cost_per_m x
		 * length. */
		double costPerMetre = 0.03;
		/** drive_speed_m_s, turn_speed_deg_s: the move, by odometry. */
		double driveSpeed = 0.25;
		double turnSpeed = mrpt::DEG2RAD(45.0);
	};

	/** A pose the robot may stand at, with its share of the belief. */
	struct Hypothesis
	{
		mrpt::math::TPose2D pose;
		double weight = 1;
	};

	/** A move: a path from the robot (at the origin) in its own frame, and
	 * the heading to face at its end (rad, robot frame). */
	struct Move
	{
		std::vector<mrpt::math::TPoint2D> path;
		double heading = 0;
		/** Share of rays that differ between the hypotheses' views. */
		double difference = 0;
		double length = 0;
		/** The end pose under the first hypothesis (world). */
		mrpt::math::TPose2D end;
	};

	/** `u` is the traversability the navigator plans on (the robot's
	 * C-space); `map` must outlive the planner. */
	ViewPlanner(
	    const SemanticMap& map, TraversabilityGrid u, const TOptions& options);

	const TOptions& options() const { return m_options; }

	/** The best move that tells the hypotheses apart (the first is the
	 * best one; at least two needed), with a path of at most `maxLength`
	 * m; nothing when no move differs by min_difference. */
	std::optional<Move> plan(
	    const std::vector<Hypothesis>& hypotheses, double maxLength) const;

	/** The view of each ray around the robot (one per degree, robot
	 * frame), at a pose of the map. */
	struct View
	{
		std::vector<float> range;
		/** Object instance label + 1 at the ray's end, 0 none, -1: the ray
		 * ends in a never-observed cell. */
		std::vector<int> what;
	};
	View view(const mrpt::math::TPose2D& pose) const;

	/** Share of the rays within the field of view around `heading` (robot
	 * frame) that differ between two views; 0 when fewer than
	 * min_known_fraction are known in both. */
	double difference(const View& a, const View& b, double heading) const;

private:
	/** Not blocked and observed at (x, y). */
	bool freeAt(double x, double y) const;
	/** freeAt (x, y) and around it at end_clearance_m. */
	bool clearAt(double x, double y) const;
	/** Mean weighted pairwise difference of the views at the best heading
	 * (returned in `heading`). */
	double score(
	    const std::vector<View>& views, const std::vector<Hypothesis>& h,
	    double& heading) const;

	const SemanticMap& m_map;
	TraversabilityGrid m_u;
	TOptions m_options;
	/** The map's occupancy, never-observed cells occupied. */
	mrpt::maps::COccupancyGridMap2D m_grid;
};

}  // namespace semnav
