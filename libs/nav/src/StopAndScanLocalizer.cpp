/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/core/format.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt/poses/CPose2D.h>
#include <semnav/common/Error.h>
#include <semnav/common/OptionTable.h>
#include <semnav/common/Timing.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/nav/NavigationErrors.h>
#include <semnav/nav/OdometryMotion.h>
#include <semnav/nav/StopAndScanLocalizer.h>
#include <semnav/robot/ControlClock.h>
#include <semnav/robot/LocalizedPose.h>
#include <semnav/robot/PoseSource.h>
#include <semnav/robot/RobotBase.h>
#include <semnav/scan/SweepSource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace semnav
{
std::string StopAndScanLocalizer::modeName(Mode m)
{
	return m == Mode::Global ? "global" : "tracking";
}

StopAndScanLocalizer::Mode StopAndScanLocalizer::modeFromName(
    const std::string& name)
{
	if (name == "global") return Mode::Global;
	if (name == "tracking") return Mode::Tracking;
	throw Error(
	    "localization mode must be global or tracking, got '" + name + "'");
}

namespace
{
/** Spread of the particles put around each hypothesis before a drive. */
constexpr double kHypothesisStdXY = 0.1;
const double kHypothesisStdYaw = mrpt::DEG2RAD(2.0);

/** The last record that ran the uniqueness check, or nullptr. */
const StopAndScanLocalizer::SweepRecord* lastChecked(
    const std::vector<StopAndScanLocalizer::SweepRecord>& records)
{
	const auto it = std::find_if(
	    records.rbegin(), records.rend(),
	    [](const StopAndScanLocalizer::SweepRecord& r) { return r.checked; });
	return it == records.rend() ? nullptr : &*it;
}

using O = StopAndScanLocalizer::TOptions;
const OptionTable<O>& optionTable()
{
	static const auto t =
	    OptionTable<O>()
	        .real(
	            "converged_fraction", &O::convergedFraction, 0.5, 1.0,
	            "Converged when this share of the particle weight lies "
	            "within...")
	        .real(
	            "converged_radius_m", &O::convergedRadius, 0.01, 10,
	            "...this distance...")
	        .angle(
	            "converged_yaw_deg", &O::convergedYaw, 0.1, 180,
	            "...and heading of the estimate.")
	        .flag(
	            "unknown_cells", &O::unknownCells,
	            "Wall samples in never-observed map cells score [WallMap] "
	            "unknown_weight.")
	        .flag(
	            "uniqueness_check", &O::uniquenessCheck,
	            "A global start is accepted only if no other place of the "
	            "map fits as well.")
	        .real(
	            "uniqueness_step_m", &O::uniquenessStep, 0.02, 5,
	            "Grid of the places scored.")
	        .real(
	            "uniqueness_margin", &O::uniquenessMargin, 0, 100,
	            "Another place within this mean log-likelihood...")
	        .real(
	            "uniqueness_min_distance_m", &O::uniquenessMinDistance, 0.05,
	            100, "...and farther than this makes a start ambiguous.")
	        .real(
	            "uniqueness_min_known_fraction", &O::uniquenessMinKnownFraction,
	            0, 1,
	            "Uniqueness check: places are scored on samples in observed "
	            "cells; fewer than this share there: not scored.")
	        .real(
	            "contradiction_distance_m", &O::contradictionDistance, 0, 100,
	            "A start is refused while an object seen twice lies where the "
	            "map observed none of its label within this (0: off).")
	        .real(
	            "missed_object_weight", &O::missedObjectWeight, 0, 100,
	            "Uniqueness check: a map object a start sweep would see at a "
	            "place but did not detect counts against it, this many "
	            "effective points (0: off).")
	        .integer(
	            "min_global_sweeps", &O::minGlobalSweeps, 1, 100,
	            "A global start is accepted after this many sweeps at least.")
	        .integer(
	            "max_sweeps", &O::maxSweeps, 1, 100,
	            "Sweeps of a start before it fails.")
	        .angle(
	            "turn_deg", &O::turnAngle, 1, 180,
	            "Turn on the spot between sweeps...")
	        .angle(
	            "turn_speed_deg_s", &O::turnSpeed, 1, 360, "...at this speed.")
	        .real(
	            "guess_std_xy_m", &O::guessStdXY, 0.001, 10,
	            "Tracking start: particle cloud around the guess.")
	        .angle(
	            "guess_std_yaw_deg", &O::guessStdYaw, 0.01, 180,
	            "Tracking start: heading spread.")
	        .integer(
	            "guess_particles", &O::guessParticles, 10, 1000000,
	            "Tracking start: particles.")
	        .real(
	            "rescan_distance_m", &O::rescanDistance, 0, 1000,
	            "Stop and scan again after this much travel (0: never).")
	        .real(
	            "rescan_min_inliers", &O::rescanMinInliers, 0, 1,
	            "A rescan whose walls fit the map less than this finds the "
	            "robot lost: global relocalization.")
	        .flag(
	            "arrival_check", &O::arrivalCheck,
	            "At the goal: turn toward it, sweep and confirm the arrival.")
	        .real(
	            "arrival_tolerance_m", &O::arrivalTolerance, 0.05, 10,
	            "An object goal is confirmed by its label seen this close to "
	            "the map's object...")
	        .integer(
	            "arrival_min_points", &O::arrivalMinPoints, 1, 100000,
	            "...as a detection or at least this many labelled points.")
	        .integer(
	            "arrival_attempts", &O::arrivalAttempts, 0, 100,
	            "Unconfirmed arrivals navigate again this many times.");
	return t;
}
}  // namespace

SEMNAV_OPTIONS_FROM_TABLE(StopAndScanLocalizer::TOptions, optionTable())

StopAndScanLocalizer::StopAndScanLocalizer(
    const SemanticMap& map, const TOptions& options,
    const MappingLocalizer::TOptions& localization,
    const PerceptionPipeline::TOptions& perception,
    const std::optional<CascadeDetector::TOptions>& cascades)
    : mrpt::system::COutputLogger("StopAndScanLocalizer"),
      m_map(map),
      m_options(options),
      m_locOptions(localization),
      m_perception(perception, cascades),
      m_semanticExtractor(localization.semanticExtractor),
      m_semantic(localization.semantic),
      m_extractor(localization.walls)
{
	// Progress goes to the log only when asked (setMinLoggingLevel): apps
	// print JSON on stdout.
	setMinLoggingLevel(mrpt::system::LVL_WARN);
	m_perception.pipeline().setMinLoggingLevel(mrpt::system::LVL_ERROR);
	if (m_locOptions.semantic.enabled()) m_semantic.build(m_map);
	makeLocalizer(m_locOptions.localizer);
	findPlaces();
}

void StopAndScanLocalizer::findPlaces()
{
	m_places.clear();
	const auto& g = m_map.geometry();
	const int stride = std::max(
	    1,
	    static_cast<int>(std::lround(m_options.uniquenessStep / g.resolution)));
	const double freeBelow = m_locOptions.localizer.freeCellThreshold;
	const auto& observations = m_map.get("observations");
	for (int cy = stride / 2; cy < g.rows; cy += stride)
		for (int cx = stride / 2; cx < g.cols; cx += stride)
			if (observations[g.index(cy, cx)] > 0 &&
			    m_map.occupancy(cx, cy) < freeBelow)
				m_places.push_back({g.centerX(cx), g.centerY(cy)});
}

void StopAndScanLocalizer::mapChanged()
{
	if (m_locOptions.semantic.enabled()) m_semantic.update(m_map);
	m_localizer->updateKnownMap(m_map);
	m_localizer->setSemanticMap(m_semantic.empty() ? nullptr : &m_semantic);
	if (m_localizer->knownWallMap().segments().empty())
		throw LocalizationFailedError(
		    "localization: the map has no walls to localize against");
	if (m_options.unknownCells)
	{
		m_walls.updateFromSemanticMap(m_map, true);
		m_localizer->setWallMap(&m_walls);
	}
	findPlaces();
	// The view planner's traversability is the old map's.
	m_viewPlanner.reset();
}

std::vector<StopAndScanLocalizer::LocalizedSweep>
StopAndScanLocalizer::takeSweeps()
{
	std::vector<LocalizedSweep> out;
	out.swap(m_kept);
	return out;
}

void StopAndScanLocalizer::keepStartSweeps(std::size_t keep)
{
	const auto trim = [keep](auto& v)
	{ v.erase(v.begin(), v.end() - std::min(keep, v.size())); };
	trim(m_startObs);
	trim(m_startSemantic);
	trim(m_startOdo);
	trim(m_startSweeps);
}

const WallMap& StopAndScanLocalizer::scoredWalls() const
{
	return m_options.unknownCells ? m_walls : m_localizer->knownWallMap();
}

void StopAndScanLocalizer::makeLocalizer(const Localizer::TOptions& o)
{
	m_localizer = std::make_unique<Localizer>(o);
	m_localizer->setMinLoggingLevel(mrpt::system::LVL_ERROR);
	m_localizer->setKnownMap(m_map);
	m_localizer->setSemanticMap(m_semantic.empty() ? nullptr : &m_semantic);
	if (m_localizer->knownWallMap().segments().empty())
		throw LocalizationFailedError(
		    "localization: the map has no walls to localize against");
	if (m_options.unknownCells)
	{
		if (m_walls.empty())
		{
			m_walls = WallMap(m_locOptions.wallMap);
			m_walls.buildFromSemanticMap(m_map, true);
		}
		m_localizer->setWallMap(&m_walls);
	}
}

StopAndScanLocalizer::~StopAndScanLocalizer() = default;

void StopAndScanLocalizer::enableViewPlanning(
    const TraversabilityGrid& u, const ViewPlanner::TOptions& options)
{
	m_viewPlanner = std::make_unique<ViewPlanner>(m_map, u, options);
}

int StopAndScanLocalizer::sweepsPerTurn() const
{
	return static_cast<int>(std::ceil(2 * M_PI / m_options.turnAngle - 1e-6));
}

bool StopAndScanLocalizer::gatherOnClearBest(SweepRecord& rec)
{
	if (!m_options.uniquenessCheck) return false;
	checkUniqueness(rec);
	rec.evidence = evidenceOf(rec);
	MRPT_LOG_INFO_FMT(
	    "uniqueness after a full turn: estimate %.3f, best other place "
	    "(%.2f, %.2f, %.1f deg) %.3f, evidence %.3f",
	    rec.score, rec.rival.x, rec.rival.y, mrpt::RAD2DEG(rec.rival.phi),
	    rec.rivalScore, rec.evidence);
	mrpt::math::TPose2D best;
	if (rec.rivalScore > rec.score + m_options.uniquenessMargin)
		best = rec.rival;
	else if (
	    rec.evidence >= m_options.uniquenessMargin &&
	    contradiction(rec.estimate).empty())
		best = rec.estimate;
	else
		return false;
	MRPT_LOG_INFO_FMT(
	    "uniqueness: (%.2f, %.2f, %.1f deg) fits clearly best: the filter "
	    "gathers there",
	    best.x, best.y, mrpt::RAD2DEG(best.phi));
	m_localizer->initializeAround({best}, kHypothesisStdXY, kHypothesisStdYaw);
	return true;
}

bool StopAndScanLocalizer::driveToLook(
    const RobotInterfaces& robot, int spotSweeps, Report& rep)
{
	if (!m_viewPlanner) return false;
	const ViewPlanner::TOptions& o = m_viewPlanner->options();
	if (!o.enabled || spotSweeps < sweepsPerTurn() ||
	    rep.drives >= o.maxDrives || rep.sweeps >= m_options.maxSweeps)
		return false;
	const std::vector<ViewPlanner::Hypothesis> h =
	    hypotheses(rep.records.back());
	const double left = std::min(o.maxDrive, o.budget - rep.driveLength);
	const auto move =
	    h.size() < 2 ? std::nullopt : m_viewPlanner->plan(h, left);
	if (!move)
	{
		MRPT_LOG_INFO_FMT(
		    "drive to look: %zu hypotheses, no place within %.1f m tells "
		    "them apart",
		    h.size(), left);
		return false;
	}
	MRPT_LOG_INFO_FMT(
	    "drive to look: %zu hypotheses; to (%.2f, %.2f, %.0f deg) if the "
	    "first holds, %.1f m, %.0f%% of the view differs",
	    h.size(), move->end.x, move->end.y, mrpt::RAD2DEG(move->end.phi),
	    move->length, 100 * move->difference);
	// What this place said of the estimate and its rival goes with them.
	// So does an object that contradicts the map at the estimate: the
	// sweeps that saw it are dropped after the drive.
	const SweepRecord* checked = lastChecked(rep.records);
	std::string contradicted;
	if (checked)
	{
		contradicted = contradiction(checked->estimate);
		if (contradicted.empty()) contradicted = carriedContradiction(*checked);
	}
	m_carried = CarriedEvidence();
	if (checked)
		m_carried = {
		    true,
		    checked->estimate,
		    checked->rival,
		    robot.base->odometry().pose,
		    checked->evidence,
		    contradicted};
	// The filter keeps every hypothesis through the drive.
	std::vector<mrpt::math::TPose2D> poses;
	for (const auto& x : h) poses.push_back(x.pose);
	m_localizer->initializeAround(poses, kHypothesisStdXY, kHypothesisStdYaw);
	rep.driveLength += OdometryMotion(robot, o.driveSpeed, o.turnSpeed)
	                       .follow(move->path, move->heading);
	rep.drives++;
	// The uniqueness check scores the sweeps from the new place.
	keepStartSweeps(0);
	return true;
}

StopAndScanLocalizer::Report StopAndScanLocalizer::start(
    const RobotInterfaces& robot, Mode mode,
    const std::optional<mrpt::math::TPose2D>& guess)
{
	const auto t0 = std::chrono::steady_clock::now();
	if (!robot.base || !robot.sweeps || !robot.clock || !robot.pose)
		throw Error(
		    "localization: the robot lacks a base, sweeps, clock or pose");
	m_started = true;
	// Sweeps are taken standing still: the first one too.
	robot.base->stop();
	m_lastOdometry = robot.base->odometry().pose;

	Report rep;
	rep.mode = mode;
	keepStartSweeps(0);
	m_carried = CarriedEvidence();
	m_inStart = true;
	if (mode == Mode::Global)
		m_localizer->initializeGlobal();
	else
	{
		if (!guess)
			throw LocalizationFailedError(
			    "localization: tracking needs a start guess");
		// A wider, denser cloud than an ordinary tracking start.
		auto o = m_locOptions.localizer;
		o.initialStdXY = m_options.guessStdXY;
		o.initialStdYaw = m_options.guessStdYaw;
		o.particles = m_options.guessParticles;
		makeLocalizer(o);
		m_localizer->initialize(mrpt::poses::CPose2D(*guess));
	}

	sweepUntilConverged(robot, mode == Mode::Global, false, rep, t0);
	report(robot, rep.estimate);
	return rep;
}

void StopAndScanLocalizer::report(
    const RobotInterfaces& robot, const mrpt::math::TPose2D& estimate)
{
	robot.pose->setEstimate(estimate, robot.base->odometry().pose);
}

void StopAndScanLocalizer::stopNow(const RobotInterfaces& robot)
{
	robot.base->stop();
	robot.clock->tick();
}

void StopAndScanLocalizer::turnInPlace(
    const RobotInterfaces& robot, double angle)
{
	OdometryMotion(robot, 0, m_options.turnSpeed).turn(angle);
}

void StopAndScanLocalizer::sweepUntilConverged(
    const RobotInterfaces& robot, bool global, bool turnFirst, Report& rep,
    std::chrono::steady_clock::time_point t0)
{
	// (m_startObs: the sweeps of rep.records the caller kept.)
	m_inStart = true;
	std::size_t segments = 0;
	for (const auto& r : rep.records) segments += r.segments;
	int spotSweeps = 0;
	bool drove = false;
	for (int k = static_cast<int>(rep.records.size()); k < m_options.maxSweeps;
	     k++)
	{
		if ((k > 0 || turnFirst) && !drove)
			turnInPlace(robot, m_options.turnAngle);
		drove = false;
		const SweepRecord r = sweepAndUpdate(robot);
		rep.records.push_back(r);
		rep.sweeps++;
		spotSweeps++;
		segments += r.segments;
		MRPT_LOG_INFO_FMT(
		    "sweep %d: %zu walls, spread %.3f m %.2f deg, error %.3f m "
		    "%.2f deg, weight near the estimate %.3f, inliers %.2f, estimate "
		    "(%.2f, %.2f, %.1f deg)%s",
		    k + 1, r.segments, r.stdXY, mrpt::RAD2DEG(r.stdYaw), r.errorXY,
		    mrpt::RAD2DEG(r.errorYaw), r.massNear, r.inliers, r.estimate.x,
		    r.estimate.y, mrpt::RAD2DEG(r.estimate.phi),
		    r.kidnapped ? ", KIDNAPPED" : "");
		if (r.kidnapped)
		{
			// The filter spread its particles over the map again: a global
			// start from this sweep on (earlier sweeps no longer relate to
			// the pose by odometry).
			global = true;
			keepStartSweeps(1);
		}
		if (r.converged) rep.ambiguous = rep.contradicted = false;
		// A global start is decided on two views at least: one sweep sees
		// half the surroundings, and a place the map barely saw can fit a
		// twin by that half alone. The uniqueness check waits for them too:
		// on half the surroundings the best other place need not be the
		// twin the filter keeps (a place where the far walls fall outside
		// the map fits a half view as well).
		const bool enoughViews =
		    !global || rep.sweeps >= m_options.minGlobalSweeps;
		if (r.converged && m_options.uniquenessCheck && global && enoughViews)
		{
			SweepRecord& rr = rep.records.back();
			checkUniqueness(rr);
			rr.evidence = evidenceOf(rr);
			m_records.back() = rr;
			MRPT_LOG_INFO_FMT(
			    "uniqueness: estimate %.3f, best other place (%.2f, %.2f, "
			    "%.1f deg) %.3f, evidence %.3f",
			    rr.score, rr.rival.x, rr.rival.y, mrpt::RAD2DEG(rr.rival.phi),
			    rr.rivalScore, rr.evidence);
			rep.ambiguous = rr.evidence < m_options.uniquenessMargin;
			rep.contradiction = contradiction(rr.estimate);
			if (rep.contradiction.empty())
				rep.contradiction = carriedContradiction(rr);
			rep.contradicted = !rep.contradiction.empty();
			if (rep.contradicted)
				MRPT_LOG_INFO_FMT("uniqueness: %s", rep.contradiction.c_str());
			if (rr.rivalScore > rr.score + m_options.uniquenessMargin)
			{
				// Another place explains the sweeps clearly better than the
				// filter's estimate: the filter starts again there.
				MRPT_LOG_INFO("uniqueness: the other place fits better");
				m_localizer->initializeAround(
				    {rr.rival}, kHypothesisStdXY, kHypothesisStdYaw);
			}
		}
		if (r.converged && !rep.ambiguous && !rep.contradicted && enoughViews)
		{
			rep.converged = true;
			break;
		}
		if (global && !r.converged && spotSweeps == sweepsPerTurn() &&
		    gatherOnClearBest(rep.records.back()))
		{
			m_records.back() = rep.records.back();
			continue;
		}
		if (global && driveToLook(robot, spotSweeps, rep))
		{
			drove = true;
			spotSweeps = 0;
		}
	}
	m_inStart = false;
	const SweepRecord& last = rep.records.back();
	rep.truth = last.truePose;
	rep.estimate = last.estimate;
	rep.errorXY = last.errorXY;
	rep.errorYaw = last.errorYaw;
	rep.ms = msSince(t0);
	const std::string what = "localization (" + modeName(rep.mode) +
	                         (rep.recovery ? ", lost while navigating" : "") +
	                         "): ";
	// The last sweep that ran the uniqueness check names the twins.
	const SweepRecord* checked = lastChecked(rep.records);
	const SweepRecord& c = checked ? *checked : last;
	if (!rep.converged && rep.ambiguous)
		throw LocalizationFailedError(
		    what + "ambiguous after " + std::to_string(rep.sweeps) +
		    mrpt::format(
		        " sweeps: the sweeps fit (%.2f, %.2f, %.0f deg) and (%.2f, "
		        "%.2f, %.0f deg) alike",
		        c.estimate.x, c.estimate.y, mrpt::RAD2DEG(c.estimate.phi),
		        c.rival.x, c.rival.y, mrpt::RAD2DEG(c.rival.phi)));
	if (!rep.converged && rep.contradicted)
		throw LocalizationFailedError(
		    what + "the sweeps contradict the map after " +
		    std::to_string(rep.sweeps) + " sweeps: " + rep.contradiction);
	if (!rep.converged)
		throw LocalizationFailedError(
		    what + "not converged after " + std::to_string(rep.sweeps) +
		    " sweeps (" + std::to_string(segments) +
		    " wall segments seen; spread " +
		    mrpt::format(
		        "%.2f m, %.1f deg)", last.stdXY, mrpt::RAD2DEG(last.stdYaw)));
}

StopAndScanLocalizer::Report StopAndScanLocalizer::rescan(
    const RobotInterfaces& robot)
{
	if (!m_started)
		throw LocalizationFailedError("localization: rescan before start");
	const auto t0 = std::chrono::steady_clock::now();
	stopNow(robot);
	Report rep;
	rep.mode = Mode::Tracking;
	rep.recovery = false;
	keepStartSweeps(0);
	m_inStart = true;
	const SweepRecord r = sweepAndUpdate(robot);
	m_inStart = false;
	rep.records.push_back(r);
	rep.sweeps = 1;
	MRPT_LOG_INFO_FMT(
	    "rescan: %zu walls, error %.3f m %.2f deg%s%s", r.segments, r.errorXY,
	    mrpt::RAD2DEG(r.errorYaw), r.converged ? "" : ", not converged",
	    r.kidnapped ? ", KIDNAPPED" : "");
	// Walls that do not fit the map at the estimate: the robot is not
	// where it believes (carried away).
	const bool disagrees =
	    !r.kidnapped && r.inliers < m_options.rescanMinInliers;
	if (r.converged && !r.kidnapped && !disagrees)
	{
		rep.converged = true;
		rep.truth = r.truePose;
		rep.estimate = r.estimate;
		rep.errorXY = r.errorXY;
		rep.errorYaw = r.errorYaw;
		rep.ms = msSince(t0);
	}
	else
	{
		// Lost (kidnapped, or the spread grew): turn and sweep as at a
		// start until converged again.
		rep.recovery = true;
		rep.mode = r.kidnapped || disagrees ? Mode::Global : Mode::Tracking;
		if (!r.kidnapped)
		{
			// Keep only the sweep a global restart started from.
			rep.records.clear();
			rep.sweeps = 0;
			keepStartSweeps(0);
		}
		if (disagrees)
		{
			MRPT_LOG_INFO_FMT(
			    "rescan: %.0f%% of the walls fit the map: relocalizing",
			    100 * r.inliers);
			m_localizer->initializeGlobal();
			// Score the next sweep (here, no turn) over the whole map.
			sweepUntilConverged(robot, true, false, rep, t0);
		}
		else
			sweepUntilConverged(robot, r.kidnapped, true, rep, t0);
	}
	report(robot, rep.estimate);
	return rep;
}

StopAndScanLocalizer::SweepRecord StopAndScanLocalizer::sweepAndUpdate(
    const RobotInterfaces& robot)
{
	const auto t0 = std::chrono::steady_clock::now();
	SweepRecord rec;
	if (robot.truth) rec.truePose = robot.truth->pose();
	rec.odometry = robot.base->odometry().pose;
	// The sweep begun now, while the robot stands still.
	if (!robot.sweeps->next(m_sweep, mrpt::Clock::now()))
		throw LocalizationFailedError(
		    std::string("localization: no sweep (") +
		    SweepSource::endName(robot.sweeps->end()) +
		    "): " + robot.sweeps->endMessage());
	const Sweep& sweep = m_sweep;
	m_perception.process(sweep, m_labeled);
	const WallObservation obs = m_extractor.extract(m_labeled);
	const SemanticObservation semantic =
	    m_semantic.empty() ? SemanticObservation()
	                       : m_semanticExtractor.extract(m_labeled);
	const mrpt::math::TPose2D odometry = sweep.odometry().asTPose();
	if (m_inStart)
	{
		m_startObs.push_back(obs);
		m_startSemantic.push_back(semantic);
		m_startOdo.push_back(odometry);
		m_startSweeps.push_back(sweep);
	}
	const mrpt::poses::CPose2D incr =
	    mrpt::poses::CPose2D(odometry) - mrpt::poses::CPose2D(m_lastOdometry);
	m_lastOdometry = odometry;
	const LocalizationUpdate u = m_localizer->update(incr, obs, &semantic);
	rec.estimate = u.pose.asTPose();
	rec.estimate.phi = mrpt::math::wrapToPi(rec.estimate.phi);
	rec.stdXY = u.stdXY;
	rec.stdYaw = u.stdYaw;
	rec.segments = obs.segments.size();
	rec.particles = u.particles;
	rec.massNear = massNear(rec.estimate);
	rec.inliers = u.inlierFraction;
	rec.kidnapped = u.kidnapped;
	// Converged: one tight hypothesis that also explains the sweep (fewer
	// inliers than the kidnap threshold is a wrong pose, however tight).
	rec.converged =
	    (u.converged || rec.massNear >= m_options.convergedFraction) &&
	    u.inlierFraction >= m_locOptions.localizer.kidnapInlierFraction;
	rec.updateMs = u.ms;
	if (robot.truth)
	{
		const mrpt::math::TPose2D now = robot.truth->pose();
		rec.errorXY =
		    std::hypot(rec.estimate.x - now.x, rec.estimate.y - now.y);
		rec.errorYaw =
		    std::abs(mrpt::math::wrapToPi(rec.estimate.phi - now.phi));
	}
	rec.ms = msSince(t0);
	m_records.push_back(rec);
	if (m_keepSweeps) m_kept.push_back({m_sweep, m_labeled, rec});
	return rec;
}

StopAndScanLocalizer::ArrivalCheck StopAndScanLocalizer::confirmArrival(
    const RobotInterfaces& robot, const NavCommand& command, int objectId)
{
	ArrivalCheck check;
	Label label = Label::Unknown;
	mrpt::math::TPoint2D target{command.x, command.y};
	if (objectId)
	{
		const ObjectInstance& o = m_map.instance(objectId);
		label = o.label;
		target = {o.centroid.x, o.centroid.y};
	}
	// Face the goal: an object beside or behind the robot is out of the
	// laser's view.
	const mrpt::math::TPose2D pose = robot.pose->pose();
	const double bearing = mrpt::math::wrapToPi(
	    std::atan2(target.y - pose.y, target.x - pose.x) - pose.phi);
	if (objectId && std::abs(bearing) > mrpt::DEG2RAD(10.0))
		turnInPlace(robot, bearing);
	const Report rep = rescan(robot);
	check.records = rep.records;
	check.estimate = rep.estimate;
	check.relocalized = rep.recovery;
	if (rep.recovery)
	{
		check.reason = "the sweep at the goal found the robot elsewhere";
		return check;
	}
	const auto detected = m_perception.objectLabels();
	check.objectChecked =
	    objectId &&
	    (label == Label::Door ||
	     std::find(detected.begin(), detected.end(), label) != detected.end());
	if (!check.objectChecked)
	{
		check.confirmed = true;
		return check;
	}
	checkObject(label, target, check);
	return check;
}

void StopAndScanLocalizer::checkObject(
    Label label, const mrpt::math::TPoint2D& target, ArrivalCheck& check) const
{
	const mrpt::poses::CPose2D at(check.estimate);
	for (const auto& d : m_labeled.detections)
	{
		if (d.label != label) continue;
		double x, y;
		at.composePoint(d.centroid.x, d.centroid.y, x, y);
		check.objectDistance = std::min(
		    check.objectDistance, std::hypot(x - target.x, y - target.y));
	}
	const double tol = m_options.arrivalTolerance;
	for (int r = 0; r < m_labeled.labels.rows; r++)
		for (int c = 0; c < m_labeled.labels.cols; c++)
		{
			if (m_labeled.label(r, c) != label) continue;
			const auto& p = m_labeled.points.at<cv::Vec3f>(r, c);
			double x, y;
			at.composePoint(p[0], p[1], x, y);
			if (std::hypot(x - target.x, y - target.y) <= tol)
				check.labelPoints++;
		}
	check.confirmed = check.objectDistance <= tol ||
	                  check.labelPoints >= m_options.arrivalMinPoints;
	if (!check.confirmed)
		check.reason = mrpt::format(
		    "no %s seen within %.2f m of (%.2f, %.2f) from the goal (%d "
		    "labelled points)",
		    labelName(label).c_str(), tol, target.x, target.y,
		    check.labelPoints);
}

}  // namespace semnav
