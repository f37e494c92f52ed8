/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/nav/NavInterfaceMonitor.h>

namespace semnav
{
NavInterfaceMonitor::NavInterfaceMonitor(mrpt::nav::CRobot2NavInterface& robot)
    : m_robot(robot)
{
	setLoggerName("NavInterfaceMonitor");
}

NavInterfaceMonitor::Events NavInterfaceMonitor::takeEvents()
{
	std::lock_guard<std::mutex> lk(m_mutex);
	Events e = m_events;
	m_events = Events();
	return e;
}

bool NavInterfaceMonitor::getCurrentPoseAndSpeeds(
    mrpt::math::TPose2D& curPose, mrpt::math::TTwist2D& curVelGlobal,
    mrpt::system::TTimeStamp& timestamp, mrpt::math::TPose2D& curOdometry,
    std::string& frameId)
{
	return m_robot.getCurrentPoseAndSpeeds(
	    curPose, curVelGlobal, timestamp, curOdometry, frameId);
}

bool NavInterfaceMonitor::changeSpeeds(
    const mrpt::kinematics::CVehicleVelCmd& cmd)
{
	return m_robot.changeSpeeds(cmd);
}
bool NavInterfaceMonitor::changeSpeedsNOP()
{
	return m_robot.changeSpeedsNOP();
}
bool NavInterfaceMonitor::stop(bool isEmergencyStop)
{
	return m_robot.stop(isEmergencyStop);
}
mrpt::kinematics::CVehicleVelCmd::Ptr NavInterfaceMonitor::getEmergencyStopCmd()
{
	return m_robot.getEmergencyStopCmd();
}
mrpt::kinematics::CVehicleVelCmd::Ptr NavInterfaceMonitor::getStopCmd()
{
	return m_robot.getStopCmd();
}
mrpt::kinematics::CVehicleVelCmd::Ptr NavInterfaceMonitor::getAlignCmd(
    const double relativeHeading)
{
	return m_robot.getAlignCmd(relativeHeading);
}
bool NavInterfaceMonitor::startWatchdog(float periodMs)
{
	return m_robot.startWatchdog(periodMs);
}
bool NavInterfaceMonitor::stopWatchdog()
{
	return m_robot.stopWatchdog();
}

bool NavInterfaceMonitor::senseObstacles(
    mrpt::maps::CSimplePointsMap& obstacles,
    mrpt::system::TTimeStamp& timestamp)
{
	mrpt::math::TPose2D pose, odo;
	mrpt::math::TTwist2D vel;
	mrpt::system::TTimeStamp t;
	std::string frame;
	const bool havePose =
	    m_robot.getCurrentPoseAndSpeeds(pose, vel, t, odo, frame);
	const bool ok = m_robot.senseObstacles(obstacles, timestamp);
	if (ok && havePose)
	{
		std::lock_guard<std::mutex> lk(m_mutex);
		m_obstacles = obstacles;
		m_obstaclesPose = pose;
		m_hasObstacles = true;
	}
	return ok;
}

void NavInterfaceMonitor::sendNavigationStartEvent()
{
	{
		std::lock_guard<std::mutex> lk(m_mutex);
		m_events.started = true;
	}
	m_robot.sendNavigationStartEvent();
}
void NavInterfaceMonitor::sendNavigationEndEvent()
{
	{
		std::lock_guard<std::mutex> lk(m_mutex);
		m_events.ended = true;
	}
	m_robot.sendNavigationEndEvent();
}
void NavInterfaceMonitor::sendWaypointReachedEvent(
    int index, bool reachedNotSkipped)
{
	{
		std::lock_guard<std::mutex> lk(m_mutex);
		m_events.waypointsReached++;
	}
	m_robot.sendWaypointReachedEvent(index, reachedNotSkipped);
}
void NavInterfaceMonitor::sendNewWaypointTargetEvent(int index)
{
	m_robot.sendNewWaypointTargetEvent(index);
}
void NavInterfaceMonitor::sendNavigationEndDueToErrorEvent()
{
	{
		std::lock_guard<std::mutex> lk(m_mutex);
		m_events.error = true;
	}
	m_robot.sendNavigationEndDueToErrorEvent();
}
void NavInterfaceMonitor::sendWaySeemsBlockedEvent()
{
	{
		std::lock_guard<std::mutex> lk(m_mutex);
		m_events.waySeemsBlocked = true;
	}
	m_robot.sendWaySeemsBlockedEvent();
}
void NavInterfaceMonitor::sendApparentCollisionEvent()
{
	{
		std::lock_guard<std::mutex> lk(m_mutex);
		m_events.apparentCollisions++;
	}
	m_robot.sendApparentCollisionEvent();
}
void NavInterfaceMonitor::sendCannotGetCloserToBlockedTargetEvent()
{
	{
		std::lock_guard<std::mutex> lk(m_mutex);
		m_events.targetBlocked = true;
	}
	m_robot.sendCannotGetCloserToBlockedTargetEvent();
}
double NavInterfaceMonitor::getNavigationTime()
{
	return m_robot.getNavigationTime();
}
void NavInterfaceMonitor::resetNavigationTimer()
{
	m_robot.resetNavigationTimer();
}

}  // namespace semnav
