/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/core/bits_math.h>
#include <semnav/common/Error.h>
#include <semnav/common/OptionTable.h>
#include <semnav/common/Printable.h>
#include <semnav/common/Timing.h>
#include <semnav/detection/SweepPerception.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/nav/NavigationErrors.h>
#include <semnav/nav/RobotNavInterface.h>
#include <semnav/planning/SemanticPlanner.h>
#include <semnav/robot/ControlClock.h>
#include <semnav/robot/LocalizedPose.h>
#include <semnav/robot/RobotBase.h>
#include <semnav/runtime/CommandQueue.h>
#include <semnav/runtime/RobotSession.h>
#include <semnav/scan/SweepSource.h>

#include <chrono>
#include <cmath>
#include <limits>

namespace semnav
{
namespace
{
using O = RobotSession::TOptions;
const OptionTable<O>& optionTable()
{
	using Mode = StopAndScanLocalizer::Mode;
	static const auto t =
	    OptionTable<O>()
	        .choice(
	            "localize", &O::localize,
	            {{Mode::Global, "global"}, {Mode::Tracking, "tracking"}},
	            "How the robot finds itself in the map at the start: global "
	            "(anywhere) or tracking (around start_pose).")
	        .reals(
	            "start_pose", &O::startPose, -1e6, 1e6,
	            "x y yaw_deg of a tracking start (map frame).")
	        .flag(
	            "grow_map", &O::growMap,
	            "Insert every localized sweep into the map as the robot "
	            "drives.")
	        .real(
	            "laser_silence_s", &O::laserSilence, 0.05, 10,
	            "No scan line for this long while driving: the base stops "
	            "until lines return.")
	        .real(
	            "odometry_timeout_s", &O::odometryTimeout, 0.05, 10,
	            "Older odometry while driving: the base stops until it "
	            "returns.")
	        .real(
	            "odometry_lost_s", &O::odometryLost, &O::odometryTimeout, 600,
	            "Odometry older than this: the command fails.")
	        .real(
	            "command_time_limit_s", &O::commandTimeLimit, 1, 1e6,
	            "A command still running after this long is cancelled.")
	        .real(
	            "status_period_s", &O::statusPeriod, 0, 3600,
	            "A status event this often while driving (0: on request "
	            "only).")
	        .real(
	            "explore_u_unobserved", &O::exploreUnobserved, 0, 1e9,
	            "Starting with no map while [Traversability] u_unobserved "
	            "blocks never-observed cells: their u (>= L: blocked).")
	        .real(
	            "unseen_rescan_m", &O::unseenRescan, 0, 100,
	            "Starting with no map: a sweep once the robot has driven this "
	            "far since the last one while its path ahead passes within its "
	            "radius of a never-observed cell (0: only every "
	            "rescan_distance_m).")
	        .real(
	            "unseen_lookahead_m", &O::unseenLookahead, 0, 100,
	            "How far ahead along the path unseen_rescan_m looks.")
	        .check(
	            [](const O& o)
	            { return o.startPose.empty() || o.startPose.size() == 3; },
	            "start_pose must be three numbers: x y yaw_deg")
	        .check(
	            [](const O& o)
	            {
		            return o.localize != StopAndScanLocalizer::Mode::Tracking ||
		                   !o.startPose.empty();
	            },
	            "localize = tracking needs start_pose");
	return t;
}

/** Farthest point goal beyond the map the grid grows for (m). */
constexpr double kExploreReach = 50.0;

}  // namespace

SEMNAV_OPTIONS_FROM_TABLE(RobotSession::TOptions, optionTable())

nlohmann::json RobotSession::poseJson(const mrpt::math::TPose2D& p)
{
	return {p.x, p.y, mrpt::RAD2DEG(p.phi)};
}

RobotSession::RobotSession(
    SemanticMap& map, const RobotInterfaces& robot, SweepObstacles& obstacles,
    const NavigationConfig& navigation,
    const MappingLocalizer::TOptions& localization,
    const PerceptionPipeline::TOptions& perception,
    const std::optional<CascadeDetector::TOptions>& cascades,
    const TOptions& options, EventSink events)
    : mrpt::system::COutputLogger("RobotSession"),
      m_map(map),
      m_robot(robot),
      m_obstacles(obstacles),
      m_config(navigation),
      m_options(options),
      m_events(std::move(events)),
      m_localization(localization),
      m_perception(perception),
      m_cascades(cascades)
{
	if (!m_robot.base || !m_robot.sweeps || !m_robot.clock || !m_robot.pose)
		throw Error("RobotSession: base, sweeps, clock and pose are needed");
	for (const auto& o : m_map.instances()) m_known.insert(o.id);
	// No map: the robot must cross space it has not seen to get anywhere.
	m_mapping = m_map.sweepsInserted() == 0 && m_map.instances().empty();
	auto& t = m_config.traversability;
	if (m_mapping && t.uUnobserved >= t.L)
		t.uUnobserved = std::min(m_options.exploreUnobserved, t.L);
}

RobotSession::~RobotSession()
{
	if (m_robot.base) m_robot.base->stop();
}

void RobotSession::emit(nlohmann::json e) const
{
	e["t"] = m_robot.clock->now();
	if (m_events) m_events(e);
}

void RobotSession::error(const std::string& line, const std::string& why)
{
	m_errors++;
	emit(
	    {{"event", "error"},
	     {"command", printable(line)},
	     {"error", printable(why)}});
}

void RobotSession::notifyObservers()
{
	if (m_observers.empty()) return;
	const auto version = m_map.version();
	const SemanticNavigator::PlanRecord* plan = nullptr;
	if (m_nav && m_nav->plans().size() != m_observedPlans)
	{
		m_observedPlans = m_nav->plans().size();
		if (m_observedPlans > 0) plan = &m_nav->plans().back();
	}
	const auto odometry = m_robot.base->odometry();
	const auto pose = m_robot.pose->pose();
	for (auto& o : m_observers)
	{
		if (o.mapVersion != version && o.observer->onMapChanged(m_map))
			o.mapVersion = version;
		if (plan) o.observer->onPlan(*plan);
		o.observer->onPose(pose, odometry.pose, odometry.time);
	}
}

void RobotSession::notifySweep(
    const Sweep& sweep, const LabeledSweep& labeled,
    const mrpt::math::TPose2D& estimate, double stdXY, double stdYaw)
{
	for (auto& o : m_observers)
		o.observer->onSweep(sweep, labeled, estimate, stdXY, stdYaw);
}

double RobotSession::odometryAge() const
{
	const auto t = m_robot.base->odometry().time;
	if (t == mrpt::Clock::time_point{})
		return std::numeric_limits<double>::infinity();
	return std::chrono::duration<double>(mrpt::Clock::now() - t).count();
}

double RobotSession::laserSilence()
{
	if (!m_lines) return 0;
	const double now = m_robot.clock->now();
	const std::size_t n = m_lines();
	if (n != m_lastLines)
	{
		m_lastLines = n;
		m_lastLineTime = now;
	}
	return now - m_lastLineTime;
}

nlohmann::json RobotSession::status() const
{
	nlohmann::json s{
	    {"event", "status"},
	    {"localized", m_localized},
	    {"pose", poseJson(m_robot.pose->pose())},
	    {"sweeps", m_sweeps},
	    {"sweeps_inserted", m_inserted},
	    {"objects", m_map.instances().size()},
	    {"commands_done", m_done},
	    {"errors", m_errors}};
	s["state"] = m_current ? "driving" : "idle";
	if (m_current) s["goal"] = m_current->text();
	if (m_nav) s["replans"] = m_nav->replans();
	return s;
}

void RobotSession::makeLocalizer()
{
	m_localizer = std::make_unique<StopAndScanLocalizer>(
	    m_map, m_config.stopAndScan, m_localization, m_perception, m_cascades);
	m_localizer->keepSweeps(true);
	if (m_config.viewPlanner.enabled)
		m_localizer->enableViewPlanning(
		    m_config.navigationTraversability(m_map), m_config.viewPlanner);
}

void RobotSession::mappingSweep()
{
	if (!m_mapper)
	{
		m_mapper = std::make_unique<MappingLocalizer>(m_localization);
		m_mapperPerception =
		    std::make_unique<SweepPerception>(m_perception, m_cascades);
		m_mapperPerception->pipeline().setMinLoggingLevel(
		    mrpt::system::LVL_ERROR);
	}
	m_robot.base->stop();
	m_robot.clock->waitFor(m_robot.clock->period());
	Sweep sweep;
	if (!m_robot.sweeps->next(sweep, mrpt::Clock::now()))
		throw LocalizationFailedError(
		    std::string("no sweep (") +
		    SweepSource::endName(m_robot.sweeps->end()) +
		    "): " + m_robot.sweeps->endMessage());
	const auto t0 = std::chrono::steady_clock::now();
	const LabeledSweep labeled = m_mapperPerception->process(sweep);
	m_obstacles.update(sweep);
	const bool first = m_map.sweepsInserted() == 0;
	const auto estimate = m_mapper->process(sweep, labeled, m_map).asTPose();
	m_robot.pose->setEstimate(estimate, sweep.odometry().asTPose());
	m_lastMappingSweepAt = m_robot.base->odometry().distance;
	m_sweeps++;
	m_inserted++;
	reportNewObjects();
	const auto& u = m_mapper->lastUpdate();
	notifySweep(sweep, labeled, estimate, u.stdXY, u.stdYaw);
	if (first)
		emit({{"event", "map_started"}, {"pose", poseJson(estimate)}});
	else
		emit(
		    {{"event", "sweep"},
		     {"estimate", poseJson(estimate)},
		     {"std_xy_m", u.stdXY},
		     {"inliers", u.inlierFraction},
		     {"inserted", true},
		     {"mapping_ms", msSince(t0)}});
}

bool RobotSession::mappingRescan(const SemanticNavigator& nav)
{
	if (!m_mapper) return false;
	const double moved =
	    m_robot.base->odometry().distance - m_lastMappingSweepAt;
	const double every = m_config.stopAndScan.rescanDistance;
	const bool due = every > 0 && moved >= every;
	const bool unseen = m_options.unseenRescan > 0 &&
	                    moved >= m_options.unseenRescan && pathAheadUnseen(nav);
	if (!due && !unseen) return false;
	mappingSweep();
	return true;
}

bool RobotSession::pathAheadUnseen(const SemanticNavigator& nav) const
{
	if (nav.plans().empty()) return false;
	const auto& path = nav.plans().back().path;
	if (path.empty()) return false;
	const auto here = m_robot.pose->pose();
	std::size_t k = 0;
	for (std::size_t i = 1; i < path.size(); i++)
		if (std::hypot(path[i].x - here.x, path[i].y - here.y) <
		    std::hypot(path[k].x - here.x, path[k].y - here.y))
			k = i;
	const GridGeometry& g = m_map.geometry();
	const double r = m_config.traversability.robotRadius;
	const int n = static_cast<int>(std::ceil(r / g.resolution));
	const auto& observations = m_map.get("observations");
	const auto unseenNear = [&](const mrpt::math::TPoint2D& p)
	{
		int cx, cy;
		if (!g.worldToCell(p.x, p.y, cx, cy)) return true;
		for (int dy = -n; dy <= n; dy++)
			for (int dx = -n; dx <= n; dx++)
			{
				if (std::hypot(dx, dy) * g.resolution > r) continue;
				const int x = cx + dx, y = cy + dy;
				if (!g.contains(y, x) || observations[g.index(y, x)] <= 0)
					return true;
			}
		return false;
	};
	double along = 0;
	for (std::size_t i = k; i < path.size(); i++)
	{
		if (i > k)
			along += std::hypot(
			    path[i].x - path[i - 1].x, path[i].y - path[i - 1].y);
		if (along > m_options.unseenLookahead) break;
		if (unseenNear(path[i])) return true;
	}
	return false;
}

bool RobotSession::confirmArrivalByMapping(SemanticNavigator& nav)
{
	mappingSweep();
	nav.notifyPoseCorrected();
	// From the corrected pose the plan is empty (in the goal region) or
	// within the distance the navigator accepts as arrived; else the
	// navigator drives on.
	if (!nav.retry(SemanticNavigator::ReplanReason::ArrivalNotConfirmed))
		return false;
	const double accepted =
	    m_config.navigator.goalAllowedDistance + m_map.geometry().resolution;
	if (nav.state() == SemanticNavigator::State::Navigating &&
	    nav.plans().back().lengthM <= accepted)
		nav.cancel(SemanticNavigator::StopReason::Reached);
	return nav.state() == SemanticNavigator::State::Reached;
}

bool RobotSession::localize()
{
	const auto t0 = std::chrono::steady_clock::now();
	try
	{
		auto mode = m_options.localize;
		std::optional<mrpt::math::TPose2D> guess;
		if (mode == StopAndScanLocalizer::Mode::Tracking)
			guess = mrpt::math::TPose2D(
			    m_options.startPose[0], m_options.startPose[1],
			    mrpt::DEG2RAD(m_options.startPose[2]));
		if (m_mapping)
		{
			if (!m_mapper) mappingSweep();
			m_localized = true;
			notifyObservers();
			emit(
			    {{"event", "localized"},
			     {"mode", "mapping"},
			     {"pose", poseJson(m_robot.pose->pose())},
			     {"sweeps", 1},
			     {"wall_s", msSince(t0) / 1000}});
			return true;
		}
		if (!m_localizer) makeLocalizer();
		emit(
		    {{"event", "localizing"},
		     {"mode", StopAndScanLocalizer::modeName(mode)}});
		const auto rep = m_localizer->start(m_robot, mode, guess);
		m_localized = true;
		insertSweeps();
		notifyObservers();
		emit(
		    {{"event", "localized"},
		     {"pose", poseJson(rep.estimate)},
		     {"sweeps", rep.sweeps},
		     {"drives_to_look", rep.drives},
		     {"std_xy_m", rep.records.empty() ? 0.0 : rep.records.back().stdXY},
		     {"wall_s", msSince(t0) / 1000}});
		return true;
	}
	catch (const Error& e)
	{
		m_robot.base->stop();
		m_localized = false;
		if (m_localizer) m_localizer->takeSweeps();
		emit({{"event", "localization_failed"}, {"error", e.what()}});
		return false;
	}
}

void RobotSession::reportNewObjects()
{
	for (const auto& o : m_map.instances())
	{
		if (!m_known.insert(o.id).second) continue;
		// Copies: json binds references; MRPT packs TPoint3D (misaligned).
		const double x = o.centroid.x, y = o.centroid.y;
		emit(
		    {{"event", "new_object"},
		     {"id", o.id},
		     {"label", labelName(o.label)},
		     {"xy", {x, y}}});
	}
}

bool RobotSession::insertSweeps()
{
	if (!m_localizer) return false;
	bool changed = false;
	for (const auto& k : m_localizer->takeSweeps())
	{
		const auto t0 = std::chrono::steady_clock::now();
		m_sweeps++;
		m_obstacles.update(k.sweep);
		const auto& r = k.record;
		const bool insert = m_options.growMap && r.converged && !r.kidnapped &&
		                    r.inliers >= m_config.stopAndScan.rescanMinInliers;
		if (insert)
		{
			m_map.insert(k.sweep, k.labeled, mrpt::poses::CPose2D(r.estimate));
			m_inserted++;
			changed = true;
		}
		notifySweep(k.sweep, k.labeled, r.estimate, r.stdXY, r.stdYaw);
		emit(
		    {{"event", "sweep"},
		     {"estimate", poseJson(r.estimate)},
		     {"std_xy_m", r.stdXY},
		     {"inliers", r.inliers},
		     {"inserted", insert},
		     {"localize_ms", r.ms},
		     {"insert_ms", msSince(t0)}});
	}
	// The localizer follows the new map once for all the sweeps taken.
	if (changed)
	{
		reportNewObjects();
		m_localizer->mapChanged();
		if (m_config.viewPlanner.enabled)
			m_localizer->enableViewPlanning(
			    m_config.navigationTraversability(m_map), m_config.viewPlanner);
	}
	return changed;
}

NavCommand RobotSession::checkedGoal(const std::string& line)
{
	const NavCommand c = NavCommand::parse(line);
	if (!m_localized) throw NavigationError("the robot is not localized");
	// A point beyond the map, when the planner may cross never-observed
	// cells (u_unobserved < L): the grid grows to hold it, up to
	// kExploreReach from the robot.
	const auto here = m_robot.pose->pose();
	if (c.kind == NavCommand::Kind::Point &&
	    m_config.traversability.uUnobserved < m_config.traversability.L &&
	    std::hypot(c.x - here.x, c.y - here.y) <= kExploreReach)
	{
		const auto& g = m_map.geometry();
		if (c.x < g.originX || c.y < g.originY || c.x >= g.maxX() ||
		    c.y >= g.maxY())
			m_map.growToInclude(c.x - 1, c.y - 1, c.x + 1, c.y + 1);
	}
	const SemanticPlanner planner(m_map, m_config.cnn, m_config.traversability);
	const auto p = m_robot.pose->pose();
	const CostProfile profile = m_config.navigationProfile();
	try
	{
		switch (c.kind)
		{
			case NavCommand::Kind::NearestLabel:
				planner.toLabel(p.x, p.y, c.label, profile);
				break;
			case NavCommand::Kind::Object:
				if (const ObjectInstance* o = m_map.object(c.objectId);
				    o && o->label != c.label)
					throw NavigationError(
					    "object " + std::to_string(c.objectId) + " is a " +
					    labelName(o->label));
				planner.toObject(p.x, p.y, c.objectId, profile);
				break;
			case NavCommand::Kind::Point:
				planner.toPoint(p.x, p.y, c.x, c.y, profile);
				break;
		}
	}
	catch (const StartBlockedError&)
	{
		// The navigator plans from the nearest free cell.
	}
	catch (const StartOutsideMapError&)
	{
	}
	return c;
}

}  // namespace semnav
