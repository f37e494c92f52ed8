/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>
#include <semnav/common/ConfigChecks.h>
#include <semnav/common/Error.h>
#include <semnav/common/Timing.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/nav/NavigationErrors.h>
#include <semnav/nav/RobotNavInterface.h>
#include <semnav/robot/ControlClock.h>
#include <semnav/robot/LocalizedPose.h>
#include <semnav/robot/RobotBase.h>
#include <semnav/runtime/CommandQueue.h>
#include <semnav/runtime/RobotSession.h>

#include <chrono>

namespace semnav
{
namespace
{
/** Seconds a laser may stay silent while the session waits for it (the
 * sweep source itself ends with DeviceLost). */
constexpr double kLaserLost = 60.0;

bool isGoTo(const std::string& line)
{
	std::string l = line.substr(0, 5);
	for (auto& ch : l) ch = static_cast<char>(std::tolower(ch));
	return l == "go to";
}
}  // namespace

struct RobotSession::Driving
{
	double lastStatus = 0;
	/** Why the session ended the drive ("" when the navigator did). */
	std::string why;
};

std::string RobotSession::finishNavLog()
{
	return m_navlog ? m_navlog->finish() : "";
}

void RobotSession::run(CommandQueue& queue, const std::atomic<bool>& stop)
{
	m_queue = &queue;
	while (!stop)
	{
		notifyObservers();
		const auto line = queue.pop(0.1);
		if (!line)
		{
			if (queue.closed()) break;
			continue;
		}
		handle(*line, stop);
	}
	m_robot.base->stop();
	m_queue = nullptr;
}

bool RobotSession::handle(
    const std::string& text, const std::atomic<bool>& stop)
{
	const std::string line = trimmed(text);
	if (line.empty()) return true;
	if (line == "status")
	{
		emit(status());
		return true;
	}
	if (line == "save map")
	{
		if (m_save) m_save();
		emit({{"event", "map_saved"}, {"sweeps_inserted", m_inserted}});
		return true;
	}
	if (line == "stop")
	{
		m_robot.base->stop();
		emit({{"event", "stopped"}});
		return true;
	}
	if (!isGoTo(line))
	{
		error(
		    line,
		    "unknown command; expected \"go to ...\", \"stop\", \"status\" "
		    "or \"save map\"");
		return false;
	}
	if (!m_localized && !localize())
	{
		error(line, "the robot is not localized");
		return false;
	}
	try
	{
		m_next = checkedGoal(line);
	}
	catch (const Error& e)
	{
		error(line, e.what());
		return false;
	}
	while (m_next && !stop)
	{
		const NavCommand c = *m_next;
		m_next.reset();
		drive(c, stop);
	}
	return true;
}

void RobotSession::drive(
    const NavCommand& command, const std::atomic<bool>& stop)
{
	if (!m_nav)
	{
		m_interface = std::make_unique<RobotNavInterface>(
		    *m_robot.base, *m_robot.pose, m_obstacles, *m_robot.clock,
		    m_config.robotInterface);
		m_interface->setMinLoggingLevel(mrpt::system::LVL_ERROR);
		m_nav = std::make_unique<SemanticNavigator>(
		    *m_interface, m_map, *m_config.mrptSections, m_config.cnn,
		    m_config.traversability, m_config.navigator);
		m_nav->setMinLoggingLevel(mrpt::system::LVL_ERROR);
		if (!m_navlogPath.empty())
			m_navlog = std::make_unique<NavLogFile>(*m_nav, m_navlogPath);
	}
	m_current = command;
	m_observedPlans = 0;
	const auto t0 = std::chrono::steady_clock::now();
	emit({{"event", "goal"}, {"command", command.text()}});
	m_nav->start(command);
	Driving d;
	d.lastStatus = m_robot.clock->now();
	m_lastLineTime = m_robot.clock->now();
	nlohmann::json done{{"command", command.text()}};
	try
	{
		runLoop(d, stop, done);
	}
	catch (const LocalizationFailedError& e)
	{
		m_localized = false;
		d.why = e.what();
	}
	m_robot.base->stop();
	insertSweeps();
	const bool reached =
	    m_nav->state() == SemanticNavigator::State::Reached && d.why.empty();
	done["event"] = reached ? "arrived" : "failed";
	if (!reached)
	{
		done["reason"] = d.why.empty() ? m_nav->stopMessage() : d.why;
		done["stop_reason"] =
		    SemanticNavigator::stopReasonName(m_nav->stopReason());
	}
	if (m_nav->goalObjectId()) done["object"] = m_nav->goalObjectId();
	done["pose"] = poseJson(m_robot.pose->pose());
	done["replans"] = m_nav->replans();
	const auto pc = m_nav->planner().counters();
	done["planner"] = {
	    {"full_fields", pc.fullFields},
	    {"repairs", pc.repairs},
	    {"repair_fallbacks", pc.repairFallbacks},
	    {"reuses", pc.reuses}};
	done["wall_s"] = msSince(t0) / 1000;
	m_plans.insert(m_plans.end(), m_nav->plans().begin(), m_nav->plans().end());
	m_current.reset();
	m_done++;
	emit(done);
}

void RobotSession::runLoop(
    Driving& d, const std::atomic<bool>& stop, nlohmann::json& done)
{
	// Mapping: the session takes the sweeps (whileDriving, arrivals).
	NavigationLoop loop(
	    *m_nav, m_robot, m_mapping ? nullptr : m_localizer.get());
	const double deadline = m_robot.clock->now() + m_options.commandTimeLimit;
	const auto run = [&]
	{
		return loop.run(
		    deadline, [&](double, SemanticNavigator& nav)
		    { whileDriving(nav, d, stop); });
	};
	const auto r = run();
	if (!m_mapping)
	{
		done["rescans"] = r.rescans.size();
		done["recoveries"] = r.recoveries;
		done["arrival_checks"] = r.arrivals.size();
		if (!r.arrivals.empty())
			done["arrival_confirmed"] = r.arrivals.back().confirmed;
		return;
	}
	for (int attempt = 0; m_nav->state() == SemanticNavigator::State::Reached;
	     attempt++)
	{
		const bool confirmed = confirmArrivalByMapping(*m_nav);
		done["arrival_checks"] = attempt + 1;
		done["arrival_confirmed"] = confirmed;
		if (confirmed || m_nav->state() != SemanticNavigator::State::Navigating)
			return;
		if (attempt >= m_config.stopAndScan.arrivalAttempts)
		{
			m_nav->cancel(SemanticNavigator::StopReason::ArrivalNotConfirmed);
			return;
		}
		run();
	}
}

void RobotSession::whileDriving(
    SemanticNavigator& nav, Driving& d, const std::atomic<bool>& stop)
{
	m_trajectory.push_back(m_robot.pose->pose());
	if (insertSweeps()) nav.notifyMapChanged();
	if (mappingRescan(nav)) nav.notifyPoseCorrected();
	notifyObservers();
	if (stop)
	{
		m_robot.base->stop();
		nav.cancel();
		return;
	}
	if (const std::string lost = waitForSensors(stop); !lost.empty())
	{
		d.why = lost;
		nav.cancel();
		return;
	}
	const double now = m_robot.clock->now();
	if (m_options.statusPeriod > 0 &&
	    now - d.lastStatus >= m_options.statusPeriod)
	{
		d.lastStatus = now;
		emit(status());
	}
	while (m_queue)
	{
		const auto line = m_queue->pop(0);
		if (!line) break;
		const std::string l = trimmed(*line);
		if (l == "stop")
		{
			m_robot.base->stop();
			d.why = "stopped by the operator";
			nav.cancel();
			return;
		}
		if (!isGoTo(l))
		{
			handle(l, stop);
			continue;
		}
		try
		{
			m_next = checkedGoal(l);
			d.why = "replaced by \"" + m_next->text() + "\"";
			nav.cancel();
			return;
		}
		catch (const Error& e)
		{
			error(l, e.what());
		}
	}
}

std::string RobotSession::waitForSensors(const std::atomic<bool>& stop)
{
	const auto why = [&]() -> std::string
	{
		if (m_lines && laserSilence() > m_options.laserSilence)
			return "laser silent";
		if (odometryAge() > m_options.odometryTimeout) return "odometry stale";
		return "";
	};
	std::string reason = why();
	if (reason.empty()) return "";
	m_robot.base->stop();
	emit({{"event", "paused"}, {"reason", reason}});
	const double since = m_robot.clock->now();
	while (!stop)
	{
		m_robot.clock->waitFor(m_robot.clock->period());
		if (odometryAge() > m_options.odometryLost)
			return mrpt::format(
			    "odometry lost: none for %.1f s", m_options.odometryLost);
		if (m_robot.clock->now() - since > kLaserLost)
			return mrpt::format(
			    "laser lost: no scan line for %.0f s", kLaserLost);
		reason = why();
		if (reason.empty())
		{
			emit(
			    {{"event", "resumed"},
			     {"paused_s", m_robot.clock->now() - since}});
			return "";
		}
		m_robot.base->stop();
	}
	return "";
}

}  // namespace semnav
