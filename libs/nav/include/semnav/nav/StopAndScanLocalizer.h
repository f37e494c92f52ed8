/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/math/TPose2D.h>
#include <mrpt/system/COutputLogger.h>
#include <semnav/detection/SweepPerception.h>
#include <semnav/localization/Localizer.h>
#include <semnav/localization/MappingLocalizer.h>
#include <semnav/localization/SemanticEvidenceMap.h>
#include <semnav/localization/SemanticExtractor.h>
#include <semnav/localization/WallExtractor.h>
#include <semnav/nav/NavCommand.h>
#include <semnav/nav/ViewPlanner.h>
#include <semnav/perception/LabeledSweep.h>
#include <semnav/perception/PerceptionPipeline.h>
#include <semnav/robot/RobotInterfaces.h>

#include <chrono>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace semnav
{
class SemanticMap;

/** Localization of a robot in a known semantic map, the way the paper's
 * robot does it (sec. 2.3): stop the base, take the next sweep taken while
 * it stood still (the robot's SweepSource), run perception (SweepPerception:
 * rules and, with cascades, the object detectors), the wall extractor and
 * the semantic extractor, and update the particle filter (Localizer on the
 * map's walls and, with [SemanticEvidence] on, its labels and objects) with
 * the odometry since the previous sweep. It sees the robot only through
 * RobotInterfaces (base, sweeps, clock, reported pose): the same code runs on a
 * robot and in the simulator.
 *
 * - start(): global (particles over the map's free cells) or tracking
 *   (particles around a rough guess). While the filter has not converged
 *   the robot turns on the spot by turn_deg and sweeps again, at most
 *   max_sweeps sweeps; then LocalizationFailedError. On success the
 *   robot's reported pose (RobotInterfaces::pose) takes the estimate.
 * - rescan(): one more stop-and-scan update during navigation; the reported
 *   pose jumps to the new estimate.
 * - With RobotInterfaces::truth (a simulation), every sweep record also
 *   holds the true pose and the estimate's error; nothing else uses it.
 *
 * Options: INI section [StopAndScan] (config/navigation.ini). */
class StopAndScanLocalizer : public mrpt::system::COutputLogger
{
public:
	enum class Mode
	{
		Global,
		Tracking
	};
	static std::string modeName(Mode m);
	/** "global" or "tracking"; throws Error otherwise. */
	static Mode modeFromName(const std::string& name);

	struct TOptions : public mrpt::config::CLoadableOptions
	{
		void loadFromConfigFile(
		    const mrpt::config::CConfigFileBase& c,
		    const std::string& section) override;
		void saveToConfigFile(
		    mrpt::config::CConfigFileBase& c,
		    const std::string& section) const override;

		/** converged_fraction, converged_radius_m, converged_yaw_deg: a
		 * sweep leaves the filter converged when its spread is below its
		 * thresholds ([Localizer]) or when at least this fraction of the
		 * particle weight lies within this distance and heading of the
		 * estimate (one dominant hypothesis; a few stray particles far
		 * away keep the spread large for many sweeps), and at least
		 * [Localizer] kidnap_inlier_fraction of its wall samples lie near
		 * a map wall at the estimate. */
		double convergedFraction = 0.95;
		double convergedRadius = 0.25;
		double convergedYaw = mrpt::DEG2RAD(3.0);
		/** unknown_cells: wall samples in cells the known map never
		 * observed score [WallMap] unknown_weight instead of the
		 * far-from-any-wall value (a map built from a few sweeps lacks
		 * walls the robot sees from elsewhere); as while mapping. */
		bool unknownCells = true;
		/** uniqueness_check: before a start is accepted, every place of the
		 * map's free space (a grid of uniqueness_step_m, headings of the
		 * estimate + k 90 deg +- 2 deg) is scored on all the start's
		 * sweeps; if another place more than uniqueness_min_distance_m
		 * away explains them within uniqueness_margin (mean
		 * log-likelihood per wall sample) of the estimate, the start is
		 * ambiguous (walls alone cannot tell, e.g. a symmetric room) and
		 * not converged. */
		bool uniquenessCheck = true;
		double uniquenessStep = 0.15;
		double uniquenessMargin = 0.07;
		double uniquenessMinDistance = 0.75;
		/** uniqueness_min_known_fraction: the uniqueness check scores each
		 * place on the samples that fall in cells the map observed (what
		 * the map does not show cannot rule a place out: a robot in a
		 * barely mapped twin room); a place where fewer than this fraction
		 * of the wall samples do is not scored. */
		double uniquenessMinKnownFraction = 0.25;
		/** contradiction_distance_m: a start is not accepted while an object
		 * the detectors found in two of its sweeps at the same place (or in
		 * its last sweep, until the next one checks it) lies,
		 * at the estimate, in a cell the map observed and farther than this
		 * from every object of its label in the map, reported or a
		 * candidate (the robot is not
		 * where it believes, even when no better place is found: its true
		 * place may be one the map barely saw); 0: off. */
		double contradictionDistance = 1.0;
		/** missed_object_weight: negative evidence in the uniqueness check.
		 * A map object that a start sweep would have in view at a place
		 * (SweepView: within the sweep's field, large enough, nothing in
		 * front in the sweep's own ranges) but whose label the detectors
		 * did not find near it counts log(1 - recall) against that place,
		 * times this weight in effective wall points; recall is the
		 * instance's detections per view in the map, within 0.3-0.8. Two
		 * twin offices differ by a wastebasket in one: from the other, not
		 * seeing it is the evidence. 0: off. */
		double missedObjectWeight = 6.0;
		/** max_sweeps: sweeps of a start before giving up. */
		int maxSweeps = 12;
		/** min_global_sweeps: a global start is accepted only after this
		 * many sweeps (turning between them): one sweep sees half the
		 * surroundings, and in a place the map barely saw that half can fit
		 * a twin room by the margin. */
		int minGlobalSweeps = 2;
		/** turn_deg: turn on the spot between start sweeps (rad). */
		double turnAngle = mrpt::DEG2RAD(60.0);
		/** turn_speed_deg_s (rad/s). */
		double turnSpeed = mrpt::DEG2RAD(45.0);
		/** guess_std_xy_m, guess_std_yaw_deg, guess_particles: the particle
		 * cloud of a tracking start around --start-guess. */
		double guessStdXY = 0.5;
		double guessStdYaw = mrpt::DEG2RAD(15.0);
		int guessParticles = 4000;
		/** rescan_distance_m: during navigation, stop and scan after this
		 * much odometry travel (0: never). */
		double rescanDistance = 1.0;
		/** rescan_min_inliers: a rescan whose wall samples fit the map at
		 * the estimate less than this (fraction within 2 sigma of a map
		 * wall) finds the robot lost: it localizes again from scratch
		 * (global, turning and sweeping). */
		double rescanMinInliers = 0.7;
		/** arrival_check: at the goal the robot turns toward it, sweeps and
		 * confirms the arrival (confirmArrival()); arrival_tolerance_m: an
		 * object goal is confirmed by a detection (or labelled points) of
		 * its label this close to the map's object; arrival_attempts:
		 * unconfirmed arrivals navigate again this many times. */
		bool arrivalCheck = true;
		double arrivalTolerance = 0.6;
		int arrivalAttempts = 2;
		/** arrival_min_points: labelled points of the goal's label near it
		 * that confirm an object goal without a detection. */
		int arrivalMinPoints = 20;
	};

	/** One sweep and its filter update. */
	struct SweepRecord
	{
		/** True pose (with RobotInterfaces::truth), estimate and the
		 * robot's odometry at the sweep. */
		mrpt::math::TPose2D truePose, estimate, odometry;
		double stdXY = 0, stdYaw = 0;
		std::size_t segments = 0;
		std::size_t particles = 0;
		/** Fraction of the particle weight near the estimate (see
		 * converged_fraction). */
		double massNear = 0;
		/** Fraction of the sweep's wall samples near a map wall at the
		 * estimate (Localizer's inlier fraction). */
		double inliers = 0;
		/** The filter detected a likelihood collapse (kidnapping) and
		 * spread its particles again. */
		bool kidnapped = false;
		/** This sweep alone meets the convergence criterion. */
		bool converged = false;
		/** Uniqueness check (when run): mean log-likelihood per wall
		 * sample of the start's sweeps at the estimate and at the best
		 * other place, and that place. */
		bool checked = false;
		double score = 0, rivalScore = 0;
		/** score - rivalScore, plus what the places seen before the last
		 * drive to look said of the same two hypotheses (carried by the
		 * drive's odometry): evidence from several places adds up. A start
		 * is ambiguous while this is below uniqueness_margin. */
		double evidence = 0;
		/** Wall clock of the check, ms. */
		double checkMs = 0;
		mrpt::math::TPose2D rival;
		/** Sweep + perception + walls + update, wall clock. */
		double ms = 0;
		/** Filter update alone (Localizer), ms. */
		double updateMs = 0;
		/** Error of the estimate against the true pose (m, rad; with
		 * RobotInterfaces::truth). */
		double errorXY = 0, errorYaw = 0;
	};

	/** Outcome of start(). */
	struct Report
	{
		Mode mode = Mode::Global;
		int sweeps = 0;
		bool converged = false;
		/** Not converged because another place explains the sweeps as
		 * well (see uniqueness_check). */
		bool ambiguous = false;
		/** Not converged because the sweeps contradict the map at the
		 * estimate (contradiction_distance_m); what was seen where. */
		bool contradicted = false;
		std::string contradiction;
		/** A rescan that found the robot lost and turned and swept until
		 * converged again. */
		bool recovery = false;
		mrpt::math::TPose2D estimate, truth;
		/** Estimate minus truth at the end of the start (m, rad). */
		double errorXY = 0, errorYaw = 0;
		/** Wall clock of the whole start, ms. */
		double ms = 0;
		/** Drives to look (enableViewPlanning) and their odometry length
		 * (m). */
		int drives = 0;
		double driveLength = 0;
		std::vector<SweepRecord> records;
	};

	/** `map` is the known map (its walls, labels, objects and free cells);
	 * it must outlive the localizer. Without `cascades` no objects are
	 * detected (labels from the rules only). Throws LocalizationFailedError
	 * when the map has no walls, ConfigError/CascadeError when a cascade
	 * cannot be loaded. */
	StopAndScanLocalizer(
	    const SemanticMap& map, const TOptions& options,
	    const MappingLocalizer::TOptions& localization,
	    const PerceptionPipeline::TOptions& perception,
	    const std::optional<CascadeDetector::TOptions>& cascades =
	        std::nullopt);
	~StopAndScanLocalizer() override;

	/** Localizes the robot where it stands (see the class comment). A
	 * tracking start needs `guess`. Throws LocalizationFailedError (also
	 * when the sweep source ends). */
	Report start(
	    const RobotInterfaces& robot, Mode mode,
	    const std::optional<mrpt::math::TPose2D>& guess = std::nullopt);

	/** One stop-and-scan update: stops the robot, sweeps, updates the
	 * filter and the robot's estimate. When that sweep leaves the filter
	 * unconverged or kidnapped (likelihood collapse: the particles were
	 * spread over the map again), the robot turns and sweeps as at a start
	 * (global after a kidnapping, with the uniqueness check) until
	 * converged; else LocalizationFailedError ("lost while navigating"). */
	Report rescan(const RobotInterfaces& robot);

	/** What the sweep at the goal said. */
	struct ArrivalCheck
	{
		bool confirmed = false;
		/** Why not (one line); empty when confirmed. */
		std::string reason;
		/** The sweep found the robot lost and relocalized it. */
		bool relocalized = false;
		/** Object goals: the nearest detection of the goal's label to the
		 * map's object (m; infinity: none) and labelled points of that
		 * label within the tolerance. */
		double objectDistance = std::numeric_limits<double>::infinity();
		int labelPoints = 0;
		/** False when the perception cannot see the goal's label (its
		 * detector is off): then the sweep fitting the map confirms it. */
		bool objectChecked = false;
		/** The estimate after the sweep. */
		mrpt::math::TPose2D estimate;
		/** The sweeps taken (one, more after a relocalization). */
		std::vector<SweepRecord> records;
	};

	/** At a goal the navigator believes reached: turns toward it, stops,
	 * sweeps (a rescan: a robot found lost is relocalized) and checks that
	 * the goal is where the map says: for an object (`objectId` of the map),
	 * a detection of its label, or arrival_min_points labelled points of
	 * it, within arrival_tolerance_m of the object; for a point, or an
	 * object whose label the perception cannot see (no detector for it), a
	 * sweep that fits the map (converged, not lost). Throws
	 * LocalizationFailedError as rescan(). */
	ArrivalCheck confirmArrival(
	    const RobotInterfaces& robot, const NavCommand& command, int objectId);

	/** Active disambiguation: a global start that stays ambiguous after
	 * a full turn on the spot drives to a place whose view tells its
	 * hypotheses apart (ViewPlanner; [ViewPlanner] budget), then sweeps
	 * again. `u` is the traversability the navigator plans on. Without
	 * this the robot only turns on the spot. */
	void enableViewPlanning(
	    const TraversabilityGrid& u, const ViewPlanner::TOptions& options);

	/** Where the robot may be after the last sweep: the filter's particle
	 * clusters (the estimate first) and the uniqueness check's rival of
	 * `rec`. */
	std::vector<ViewPlanner::Hypothesis> hypotheses(
	    const SweepRecord& rec) const;

	/** A sweep kept for the map (keepSweeps()): the sweep, its labels and
	 * its filter update (the estimate is the pose at the sweep). */
	struct LocalizedSweep
	{
		Sweep sweep;
		LabeledSweep labeled;
		SweepRecord record;
	};
	/** Keep every sweep with its labels and update until takeSweeps(), so
	 * the owner can insert them into the map (a map that grows as the
	 * robot drives). Off by default. */
	void keepSweeps(bool keep) { m_keepSweeps = keep; }
	/** The sweeps kept since the last call (oldest first). */
	std::vector<LocalizedSweep> takeSweeps();
	/** The map changed (sweeps inserted, the grid grown): rebuilds the
	 * walls, free places and semantic evidence the filter scores against;
	 * the particles are kept. Throws LocalizationFailedError when the map
	 * has no walls. */
	void mapChanged();

	/** Every sweep so far (start and rescans). */
	const std::vector<SweepRecord>& records() const { return m_records; }
	const TOptions& options() const { return m_options; }
	const Localizer& localizer() const { return *m_localizer; }

private:
	SweepRecord sweepAndUpdate(const RobotInterfaces& robot);
	/** Turns on the spot by `angle` (rad, by odometry) at turn_speed_deg_s,
	 * one command per control period, then stops. */
	void turnInPlace(const RobotInterfaces& robot, double angle);
	/** Stops the base and lets one control period pass. */
	static void stopNow(const RobotInterfaces& robot);
	/** The robot reports `estimate` from now on. */
	static void report(
	    const RobotInterfaces& robot, const mrpt::math::TPose2D& estimate);
	/** Sweeps (turning between them; also before the first when
	 * `turnFirst`) until converged, appending to rep (which may hold
	 * sweeps already); fills rep; throws LocalizationFailedError. */
	void sweepUntilConverged(
	    const RobotInterfaces& robot, bool global, bool turnFirst, Report& rep,
	    std::chrono::steady_clock::time_point t0);
	/** After `spotSweeps` sweeps where the robot stands: drives to look
	 * when enabled and within budget. True when it drove. */
	bool driveToLook(const RobotInterfaces& robot, int spotSweeps, Report& rep);
	/** Start sweeps in one full turn on the spot. */
	int sweepsPerTurn() const;
	/** After a full turn without convergence: when the uniqueness check
	 * finds one place that explains the start's sweeps clearly best (by
	 * uniqueness_margin; the filter may still split between twins that
	 * only the missed objects tell apart), the filter gathers there and
	 * true is returned; the next sweeps confirm it. */
	bool gatherOnClearBest(SweepRecord& rec);
	/** New Localizer with options `o` on the known map. */
	void makeLocalizer(const Localizer::TOptions& o);
	/** Best score of the start's sweeps over the free space, away from
	 * `estimate` (fills rec.score, rivalScore, rival). */
	void checkUniqueness(SweepRecord& rec) const;
	/** The scored wall map. */
	const WallMap& scoredWalls() const;
	/** Checks the last sweep's detections and labels against an object. */
	void checkObject(
	    Label label, const mrpt::math::TPoint2D& target,
	    ArrivalCheck& check) const;
	/** Drops the start's sweeps but the last `keep`. */
	void keepStartSweeps(std::size_t keep);
	/** Fraction of the particle weight within convergedRadius and
	 * convergedYaw of `estimate`. */
	double massNear(const mrpt::math::TPose2D& estimate) const;

	const SemanticMap& m_map;
	TOptions m_options;
	MappingLocalizer::TOptions m_locOptions;
	SweepPerception m_perception;
	SemanticExtractor m_semanticExtractor;
	SemanticEvidenceMap m_semantic;
	WallExtractor m_extractor;
	std::unique_ptr<Localizer> m_localizer;
	std::unique_ptr<ViewPlanner> m_viewPlanner;
	/** Scored walls when unknownCells. */
	WallMap m_walls;
	bool m_started = false;
	Sweep m_sweep;
	LabeledSweep m_labeled;
	std::vector<SweepRecord> m_records;
	/** The current start's observations and odometry at each. */
	std::vector<WallObservation> m_startObs;
	std::vector<SemanticObservation> m_startSemantic;
	std::vector<mrpt::math::TPose2D> m_startOdo;
	/** The start's sweeps (for what each had in view). */
	std::vector<Sweep> m_startSweeps;
	/** Free places of the map on the uniqueness grid. */
	std::vector<mrpt::math::TPoint2D> m_places;
	/** Fills m_places from the map. */
	void findPlaces();
	bool m_keepSweeps = false;
	std::vector<LocalizedSweep> m_kept;
	mrpt::math::TPose2D m_lastOdometry;
	bool m_inStart = false;
	/** What the uniqueness check said before the last drive to look: the
	 * estimate and its rival, the evidence between them and the odometry
	 * there (valid while a start drives). */
	struct CarriedEvidence
	{
		bool valid = false;
		mrpt::math::TPose2D estimate, rival, odometry;
		double evidence = 0;
		/** What contradicted the map at the estimate (empty: nothing). */
		std::string contradiction;
	};
	CarriedEvidence m_carried;
	/** rec.score - rec.rivalScore plus m_carried's evidence when rec's
	 * estimate and rival are the carried ones (or swapped: minus). */
	double evidenceOf(const SweepRecord& rec) const;
	/** The first object the start's sweeps saw twice that contradicts the
	 * map at `estimate` (see contradiction_distance_m), one line; empty
	 * when none. */
	std::string contradiction(const mrpt::math::TPose2D& estimate) const;
	/** `p`, a pose of m_carried, moved by the odometry from the drive to
	 * `rec`. */
	mrpt::math::TPose2D carriedTo(
	    const mrpt::math::TPose2D& p, const SweepRecord& rec) const;
	/** m_carried's contradiction when rec's estimate is the carried
	 * estimate moved by the odometry since; empty otherwise. */
	std::string carriedContradiction(const SweepRecord& rec) const;
	/** The negative evidence of missed_object_weight for the robot at
	 * `at` after the last start sweep, in the uniqueness check's units
	 * (<= 0); `missed` counts the misses. */
	double missedObjects(const mrpt::math::TPose2D& at, int& missed) const;
};

}  // namespace semnav
