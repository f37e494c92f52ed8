/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/core/format.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt/poses/CPoint2D.h>
#include <mrpt/poses/CPose2D.h>
#include <semnav/common/OptionTable.h>
#include <semnav/common/Timing.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/nav/NavigationErrors.h>
#include <semnav/nav/SemanticNavigator.h>
#include <semnav/nav/WaypointBuilder.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <set>

namespace semnav
{
namespace
{
/** MRPT's navigator with its delay statistics off (its destructor would
 * print them on stdout). */
class QuietNavigator : public mrpt::nav::CReactiveNavigationSystem
{
public:
	QuietNavigator(
	    mrpt::nav::CRobot2NavInterface& robot, const std::string& dir)
	    : mrpt::nav::CReactiveNavigationSystem(robot, false, false, dir)
	{
		m_timlog_delays.enable(false);
	}
};

std::string makeTempDir()
{
	static std::atomic<int> counter{0};
	const auto dir = std::filesystem::temp_directory_path() /
	                 ("semnav-ptg-" + std::to_string(::getpid()) + "-" +
	                  std::to_string(counter++));
	std::filesystem::create_directories(dir);
	return dir.string();
}
}  // namespace

namespace
{
using O = SemanticNavigator::TOptions;
const OptionTable<O>& optionTable()
{
	static const auto t =
	    OptionTable<O>()
	        .custom(
	            "profile",
	            [](O& o, const mrpt::config::CConfigFileBase& c,
	               const std::string& s)
	            {
		            o.profile = c.read_string(s, "profile", o.profile);
		            if (o.profile == "planning") return;
		            try
		            {
			            costProfileFromName(o.profile);
		            }
		            catch (const Error& e)
		            {
			            throw ConfigError("[" + s + "] profile: " + e.what());
		            }
	            },
	            [](const O& o) { return o.profile; },
	            "Cost profile: shortest | safe | planning (planning.ini's).")
	        .real(
	            "max_waypoint_spacing_m", &O::maxWaypointSpacing, 0.1, 100,
	            "Longest straight leg between two waypoints of the thinned "
	            "CNN path.")
	        .real(
	            "waypoint_allowed_distance_m", &O::waypointAllowedDistance,
	            0.01, 10, "An intermediate waypoint is reached this close.")
	        .real(
	            "goal_allowed_distance_m", &O::goalAllowedDistance, 0.01, 10,
	            "The goal is reached this close.")
	        .integer(
	            "max_stalled_replans", &O::maxStalledReplans, 0, 100000,
	            "Replans in a row without progress before the navigation "
	            "fails.")
	        .real(
	            "progress_m", &O::progressDistance, 0, 1000,
	            "Progress: a path this much shorter than the shortest since "
	            "the last progress...")
	        .real(
	            "progress_area_m2", &O::progressArea, 0, 1e6,
	            "...or this much more of the world observed by the map.")
	        .real(
	            "path_check_distance_m", &O::pathCheckDistance, 0, 100,
	            "Look-ahead along the path for sensed obstacles the map "
	            "lacks.")
	        .real(
	            "path_clearance_m", &O::pathClearance, 0, 10,
	            "Such an obstacle this close to the path blocks it.")
	        .integer(
	            "path_blocked_steps", &O::pathBlockedSteps, 1, 1000,
	            "Steps the path must be seen blocked before a replan.")
	        .real(
	            "sensed_obstacle_range_m", &O::sensedObstacleRange, 0, 100,
	            "On a replan, sensed points this close become obstacles.")
	        .real(
	            "align_threshold_deg", &O::alignThresholdDeg, 0, 180,
	            "First waypoint more off the heading: turn on the spot "
	            "first.")
	        .real(
	            "start_snap_m", &O::startSnap, 0, 10,
	            "A replan from a blocked cell starts from the nearest free "
	            "cell this close.");
	return t;
}
}  // namespace

SEMNAV_OPTIONS_FROM_TABLE(SemanticNavigator::TOptions, optionTable())

SemanticNavigator::SemanticNavigator(
    mrpt::nav::CRobot2NavInterface& robot, const SemanticMap& map,
    const mrpt::config::CConfigFileBase& navConfig,
    const CnnPlanner::TOptions& cnn,
    const TraversabilityBuilder::TOptions& traversability,
    const TOptions& options)
    : mrpt::system::COutputLogger("SemanticNavigator"),
      m_monitor(robot),
      m_map(map),
      m_planner(map, cnn, traversability),
      m_options(options),
      m_profile(
          options.profile == "planning" ? traversability.profile
                                        : costProfileFromName(options.profile))
{
	// MRPT reads its own sections; the PTG collision-grid cache goes to a
	// private temporary directory (removed by the destructor).
	mrpt::config::CConfigFileMemory cfg;
	std::vector<std::string> sections;
	navConfig.getAllSections(sections);
	for (const auto& s : sections)
	{
		std::vector<std::string> keys;
		navConfig.getAllKeys(s, keys);
		for (const auto& k : keys)
			cfg.write(s, k, navConfig.read_string(s, k, ""));
	}
	m_ptgCacheDir = makeTempDir();
	// PTG collision grids take about a second to build: they are shared
	// between runs through <tmp>/semnav-ptg-cache/<hash of MRPT's
	// sections>/, copied in before initialize() and published after it by
	// rename (atomic), so concurrent runs never read a partial file.
	std::string all;
	for (const auto& s : sections)
	{
		std::vector<std::string> keys;
		cfg.getAllKeys(s, keys);
		for (const auto& k : keys)
			all += s + "/" + k + "=" + cfg.read_string(s, k, "") + "\n";
	}
	char hex[32];
	std::snprintf(hex, sizeof(hex), "%016zx", std::hash<std::string>()(all));
	const auto shared =
	    std::filesystem::temp_directory_path() / "semnav-ptg-cache" / hex;
	std::error_code ec;
	if (std::filesystem::is_directory(shared, ec))
		for (const auto& e : std::filesystem::directory_iterator(shared, ec))
			if (e.path().extension() == ".gz")
				std::filesystem::copy_file(
				    e.path(),
				    std::filesystem::path(m_ptgCacheDir) / e.path().filename(),
				    ec);

	m_nav = std::make_unique<QuietNavigator>(m_monitor, m_ptgCacheDir);
	m_nav->setMinLoggingLevel(mrpt::system::LVL_ERROR);
	m_nav->enableTimeLog(false);
	m_nav->loadConfigFile(cfg);
	// Not an INI key in MRPT 2.5: set it directly.
	m_nav->params_abstract_ptg_navigator.ptg_cache_files_directory =
	    m_ptgCacheDir;
	m_nav->initialize();
	std::filesystem::create_directories(shared, ec);
	for (const auto& e : std::filesystem::directory_iterator(m_ptgCacheDir, ec))
	{
		const auto dst = shared / e.path().filename();
		if (e.path().extension() != ".gz" || std::filesystem::exists(dst, ec))
			continue;
		const auto tmp = shared / (e.path().filename().string() + ".tmp" +
		                           std::to_string(::getpid()));
		std::filesystem::copy_file(e.path(), tmp, ec);
		if (!ec) std::filesystem::rename(tmp, dst, ec);
		if (ec) std::filesystem::remove(tmp, ec);
	}
}

SemanticNavigator::~SemanticNavigator()
{
	m_nav.reset();
	std::error_code ec;
	std::filesystem::remove_all(m_ptgCacheDir, ec);
}

void SemanticNavigator::setNavLogDirectory(const std::string& dir)
{
	if (dir.empty())
	{
		m_nav->enableLogFile(false);
		return;
	}
	m_nav->setLogFileDirectory(dir);
	m_nav->enableLogFile(true);
}

mrpt::math::TPose2D SemanticNavigator::robotPose()
{
	mrpt::math::TPose2D pose, odo;
	mrpt::math::TTwist2D vel;
	mrpt::system::TTimeStamp t;
	std::string frame;
	if (!m_monitor.getCurrentPoseAndSpeeds(pose, vel, t, odo, frame))
		throw NavigationError("the robot does not report its pose");
	return pose;
}

const char* SemanticNavigator::stopReasonName(StopReason r)
{
	switch (r)
	{
		case StopReason::None:
			return "none";
		case StopReason::Reached:
			return "reached";
		case StopReason::NoPath:
			return "no_path";
		case StopReason::StartBlocked:
			return "start_blocked";
		case StopReason::GoalBlocked:
			return "goal_blocked";
		case StopReason::NoProgress:
			return "no_progress";
		case StopReason::Timeout:
			return "timeout";
		case StopReason::Cancelled:
			return "cancelled";
		case StopReason::ArrivalNotConfirmed:
			return "arrival_not_confirmed";
	}
	return "?";
}

const char* SemanticNavigator::replanReasonName(ReplanReason r)
{
	switch (r)
	{
		case ReplanReason::Initial:
			return "initial";
		case ReplanReason::WayBlocked:
			return "way_blocked";
		case ReplanReason::TargetBlocked:
			return "target_blocked";
		case ReplanReason::NavigatorError:
			return "navigator_error";
		case ReplanReason::PathBlockedBySensedObstacle:
			return "path_blocked_by_sensed_obstacle";
		case ReplanReason::MapChanged:
			return "map_changed";
		case ReplanReason::ArrivalNotConfirmed:
			return "arrival_not_confirmed";
		case ReplanReason::Relocalized:
			return "relocalized";
	}
	return "?";
}

SemanticPlanner::SharedPlan SemanticNavigator::planFrom(double x, double y)
{
	switch (m_command.kind)
	{
		case NavCommand::Kind::NearestLabel:
			return m_planner.toLabelShared(x, y, m_command.label, m_profile);
		case NavCommand::Kind::Object:
		{
			const ObjectInstance* o = m_map.object(m_command.objectId);
			if (o && o->label != m_command.label)
				throw NavigationError(
				    "object " + std::to_string(o->id) + " is a " +
				    labelName(o->label) + ", not a " +
				    labelName(m_command.label));
			return m_planner.toObjectShared(
			    x, y, m_command.objectId, m_profile);
		}
		default:
			return m_planner.toPointShared(
			    x, y, m_command.x, m_command.y, m_profile);
	}
}

SemanticPlanner::SharedPlan SemanticNavigator::planFromNearestFree(
    const mrpt::math::TPose2D& pose)
{
	try
	{
		return planFrom(pose.x, pose.y);
	}
	catch (const StartBlockedError&)
	{
		// The robot brushed an inflated obstacle (or a sensed one), or was
		// localized there: start from the nearest free cell within
		// start_snap_m.
		const TraversabilityGrid u = m_planner.traversability(m_profile);
		const GridGeometry& g = u.geometry();
		const int r =
		    static_cast<int>(std::ceil(m_options.startSnap / g.resolution));
		int cx, cy;
		g.worldToCell(pose.x, pose.y, cx, cy);
		double bestD = 1e300, bx = 0, by = 0;
		for (int dy = -r; dy <= r; dy++)
			for (int dx = -r; dx <= r; dx++)
			{
				const int row = cy + dy, col = cx + dx;
				if (!g.contains(row, col) || u.blocked(row, col)) continue;
				const double d = std::hypot(dx, dy) * g.resolution;
				if (d < bestD && d <= m_options.startSnap)
				{
					bestD = d;
					bx = g.centerX(col);
					by = g.centerY(row);
				}
			}
		if (bestD > 1e299) throw;
		return planFrom(bx, by);
	}
}

void SemanticNavigator::start(const NavCommand& command)
{
	m_command = command;
	m_plans.clear();
	m_reason = StopReason::None;
	m_message.clear();
	m_mapChanged = false;
	m_blockedSteps = 0;
	m_monitor.takeEvents();
	m_state = State::Navigating;
	// The first plan's errors (no such object, bad start, no path) are the
	// caller's input errors: they propagate.
	const auto t0 = std::chrono::steady_clock::now();
	const mrpt::math::TPose2D pose = robotPose();
	SemanticPlanner::SharedPlan plan;
	try
	{
		plan = planFromNearestFree(pose);
	}
	catch (...)
	{
		m_state = State::Failed;
		throw;
	}
	PlanRecord rec;
	rec.reason = ReplanReason::Initial;
	rec.time = m_monitor.getNavigationTime();
	rec.from = pose;
	rec.path = plan.path.points;
	rec.cost = plan.path.cost;
	rec.lengthM = plan.path.lengthM;
	rec.goalObjectId = plan.goalObjectId;
	rec.waypoints =
	    WaypointBuilder::thin(plan.path, *plan.u, m_options.maxWaypointSpacing);
	m_goalObjectId = plan.goalObjectId;
	m_lastPlanMs = rec.milliseconds = msSince(t0);
	m_plans.push_back(rec);
	trackProgress(rec.lengthM, true);
	MRPT_LOG_INFO_FMT(
	    "%s: path %.2f m, cost %.3f, %zu waypoints%s", command.text().c_str(),
	    rec.lengthM, rec.cost, rec.waypoints.size() - 1,
	    m_goalObjectId
	        ? (" to object " + std::to_string(m_goalObjectId)).c_str()
	        : "");
	if (rec.waypoints.size() < 2)
	{
		m_state = State::Reached;
		m_reason = StopReason::Reached;
		m_message = "already at the goal";
		return;
	}
	sendWaypoints();
}

double SemanticNavigator::bearingToFirstWaypoint()
{
	const auto& w = m_plans.back().waypoints;
	const mrpt::math::TPose2D p = robotPose();
	const auto& t = w.size() > 1 ? w[1] : w[0];
	return mrpt::math::wrapToPi(std::atan2(t.y - p.y, t.x - p.x) - p.phi);
}

void SemanticNavigator::sendWaypoints()
{
	// MRPT compiles its score formulas on the first candidate it scores; a
	// first target behind a differential drive is outside every PTG's
	// domain and leaves that candidate without target variables (compile
	// error). Turning toward the path first avoids it, and is what a
	// differential drive does anyway.
	m_aligning = std::abs(bearingToFirstWaypoint()) >
	                 m_options.alignThresholdDeg * M_PI / 180 &&
	             m_monitor.getAlignCmd(bearingToFirstWaypoint()) != nullptr;
	if (m_aligning) return;
	m_nav->navigateWaypoints(WaypointBuilder::toSequence(
	    m_plans.back().waypoints, m_options.waypointAllowedDistance,
	    m_options.goalAllowedDistance));
}

void SemanticNavigator::stopWith(StopReason r, const std::string& message)
{
	m_state = r == StopReason::Reached ? State::Reached : State::Failed;
	m_reason = r;
	m_message = message;
	m_nav->cancel();
	if (r != StopReason::Reached)
		MRPT_LOG_WARN_FMT("navigation stopped: %s", message.c_str());
}

void SemanticNavigator::cancel(StopReason reason)
{
	if (m_state == State::Navigating)
		stopWith(reason, std::string("navigation ") + stopReasonName(reason));
}

bool SemanticNavigator::retry(ReplanReason reason)
{
	if (m_state == State::Navigating || m_state == State::Idle)
		return m_state == State::Navigating;
	m_state = State::Navigating;
	m_reason = StopReason::None;
	m_message.clear();
	m_planner.setExtraObstacles({});
	m_stalled = 0;
	m_bestLength = std::numeric_limits<double>::infinity();
	return replan(reason);
}

void SemanticNavigator::trackProgress(double lengthM, bool first)
{
	const std::size_t seen = observedCells();
	const double res = m_map.geometry().resolution;
	const double newArea =
	    seen > m_seenAtProgress ? (seen - m_seenAtProgress) * res * res : 0;
	if (first || lengthM <= m_bestLength - m_options.progressDistance ||
	    newArea >= m_options.progressArea)
	{
		m_stalled = 0;
		m_bestLength = lengthM;
		m_seenAtProgress = seen;
	}
	else
	{
		m_stalled++;
		m_bestLength = std::min(m_bestLength, lengthM);
	}
}

std::size_t SemanticNavigator::observedCells() const
{
	if (!m_map.exists("observations")) return 0;
	const auto& obs = m_map.get("observations");
	return static_cast<std::size_t>(
	    std::count_if(obs.begin(), obs.end(), [](float v) { return v > 0; }));
}

void SemanticNavigator::refuseArrival(const std::string& why)
{
	if (m_state == State::Reached)
		stopWith(StopReason::ArrivalNotConfirmed, why);
}

void SemanticNavigator::addSensedObstacles()
{
	if (!m_monitor.hasObstacles() || m_options.sensedObstacleRange <= 0) return;
	const auto& obs = m_monitor.lastObstacles();
	const mrpt::poses::CPose2D at(m_monitor.lastObstaclesPose());
	const GridGeometry& g = m_map.geometry();
	auto pts = m_planner.extraObstacles();
	std::set<std::size_t> have;
	for (const auto& p : pts)
		if (const auto c = g.cellOf(p.x, p.y)) have.insert(g.index(*c));
	const double r2 = std::pow(m_options.sensedObstacleRange, 2);
	for (std::size_t i = 0; i < obs.size(); i++)
	{
		float lx, ly, lz;
		obs.getPoint(i, lx, ly, lz);
		if (lx * lx + ly * ly > r2) continue;
		const mrpt::poses::CPoint2D w = at + mrpt::poses::CPoint2D(lx, ly);
		const auto c = g.cellOf(w.x(), w.y());
		if (!c || knownObstacle(w.x(), w.y()) ||
		    !have.insert(g.index(*c)).second)
			continue;
		pts.push_back({w.x(), w.y()});
	}
	m_planner.setExtraObstacles(std::move(pts));
}

bool SemanticNavigator::knownObstacle(double x, double y) const
{
	const GridGeometry& g = m_map.geometry();
	int cx, cy;
	if (!g.worldToCell(x, y, cx, cy)) return false;
	for (int dy = -1; dy <= 1; dy++)
		for (int dx = -1; dx <= 1; dx++)
			if (g.contains(cy + dy, cx + dx) &&
			    m_map.cellState(cx + dx, cy + dy) ==
			        SemanticMap::CellState::Occupied)
				return true;
	return false;
}

bool SemanticNavigator::pathBlocked()
{
	if (m_plans.empty() || !m_monitor.hasObstacles()) return false;
	const auto& path = m_plans.back().path;
	if (path.size() < 2) return false;
	const mrpt::poses::CPose2D at(m_monitor.lastObstaclesPose());
	// Path points from the one nearest the robot, up to the look-ahead.
	std::size_t k0 = 0;
	double best = 1e300;
	for (std::size_t k = 0; k < path.size(); k++)
	{
		const double d = std::hypot(path[k].x - at.x(), path[k].y - at.y());
		if (d < best)
		{
			best = d;
			k0 = k;
		}
	}
	std::vector<mrpt::math::TPoint2D> ahead;
	double along = 0;
	for (std::size_t k = k0; k < path.size(); k++)
	{
		if (k > k0)
			along += std::hypot(
			    path[k].x - path[k - 1].x, path[k].y - path[k - 1].y);
		if (along > m_options.pathCheckDistance) break;
		ahead.push_back(path[k]);
	}
	const double c2 = m_options.pathClearance * m_options.pathClearance;
	const auto& obs = m_monitor.lastObstacles();
	for (std::size_t i = 0; i < obs.size(); i++)
	{
		float lx, ly, lz;
		obs.getPoint(i, lx, ly, lz);
		const mrpt::poses::CPoint2D w = at + mrpt::poses::CPoint2D(lx, ly);
		bool near = false;
		for (const auto& p : ahead)
			if (std::pow(p.x - w.x(), 2) + std::pow(p.y - w.y(), 2) < c2)
			{
				near = true;
				break;
			}
		if (near && !knownObstacle(w.x(), w.y())) return true;
	}
	return false;
}

bool SemanticNavigator::replan(ReplanReason reason)
{
	const auto t0 = std::chrono::steady_clock::now();
	if (reason != ReplanReason::MapChanged && reason != ReplanReason::Initial)
		addSensedObstacles();
	const mrpt::math::TPose2D pose = robotPose();
	SemanticPlanner::SharedPlan plan;
	try
	{
		plan = planFromNearestFree(pose);
	}
	catch (const NoPathError& e)
	{
		stopWith(StopReason::NoPath, e.what());
		return false;
	}
	catch (const EmptyGoalError& e)
	{
		stopWith(StopReason::GoalBlocked, e.what());
		return false;
	}
	catch (const StartBlockedError& e)
	{
		stopWith(StopReason::StartBlocked, e.what());
		return false;
	}
	catch (const StartOutsideMapError& e)
	{
		stopWith(StopReason::StartBlocked, e.what());
		return false;
	}
	PlanRecord rec;
	rec.reason = reason;
	rec.time = m_monitor.getNavigationTime();
	rec.from = pose;
	rec.path = plan.path.points;
	rec.path.insert(rec.path.begin(), {pose.x, pose.y});
	rec.cost = plan.path.cost;
	rec.lengthM = plan.path.lengthM;
	rec.goalObjectId = plan.goalObjectId;
	rec.waypoints =
	    WaypointBuilder::thin(plan.path, *plan.u, m_options.maxWaypointSpacing);
	m_goalObjectId = plan.goalObjectId;
	m_lastPlanMs = rec.milliseconds = msSince(t0);
	m_plans.push_back(rec);
	trackProgress(rec.lengthM, false);
	MRPT_LOG_INFO_FMT(
	    "replan #%d (%s) at (%.2f, %.2f): path %.2f m, %zu waypoints, %.1f ms",
	    replans(), replanReasonName(reason), pose.x, pose.y, rec.lengthM,
	    rec.waypoints.size() - 1, rec.milliseconds);
	m_blockedSteps = 0;
	m_nav->resetNavError();
	if (rec.waypoints.size() < 2)
	{
		stopWith(StopReason::Reached, "reached");
		return true;
	}
	sendWaypoints();
	return true;
}

SemanticNavigator::State SemanticNavigator::step()
{
	if (m_state != State::Navigating) return m_state;
	const auto t0 = std::chrono::steady_clock::now();
	if (m_aligning)
	{
		const double b = bearingToFirstWaypoint();
		if (std::abs(b) < 15 * M_PI / 180)
		{
			m_monitor.stop(false);
			m_aligning = false;
			m_nav->navigateWaypoints(WaypointBuilder::toSequence(
			    m_plans.back().waypoints, m_options.waypointAllowedDistance,
			    m_options.goalAllowedDistance));
		}
		else if (const auto cmd = m_monitor.getAlignCmd(b))
			m_monitor.changeSpeeds(*cmd);
		m_lastStepMs = msSince(t0);
		return m_state;
	}
	m_nav->navigationStep();
	const auto ev = m_monitor.takeEvents();
	const auto status = m_nav->getWaypointNavStatus();
	if (status.final_goal_reached || ev.ended)
	{
		stopWith(StopReason::Reached, "reached");
		m_lastStepMs = msSince(t0);
		return m_state;
	}
	std::optional<ReplanReason> why;
	if (ev.waySeemsBlocked)
		why = ReplanReason::WayBlocked;
	else if (ev.targetBlocked)
		why = ReplanReason::TargetBlocked;
	else if (
	    ev.error ||
	    m_nav->getCurrentState() == mrpt::nav::CAbstractNavigator::NAV_ERROR)
		why = ReplanReason::NavigatorError;
	else if (m_mapChanged)
		why = ReplanReason::MapChanged;
	else if (pathBlocked())
	{
		if (++m_blockedSteps >= m_options.pathBlockedSteps)
			why = ReplanReason::PathBlockedBySensedObstacle;
	}
	else
		m_blockedSteps = 0;
	if (why)
	{
		m_mapChanged = false;
		if (m_stalled >= m_options.maxStalledReplans)
			stopWith(
			    StopReason::NoProgress, "no progress in " +
			                                std::to_string(m_stalled) +
			                                " replans (no path shorter than " +
			                                mrpt::format("%.2f", m_bestLength) +
			                                " m, no new space seen)");
		else
			replan(*why);
	}
	m_lastStepMs = msSince(t0);
	return m_state;
}

}  // namespace semnav
