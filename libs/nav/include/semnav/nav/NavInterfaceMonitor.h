/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/math/TPose2D.h>
#include <mrpt/nav/reactive/CRobot2NavInterface.h>

#include <mutex>

namespace semnav
{
/** A CRobot2NavInterface that forwards every call to the robot's own
 * interface (real or simulated) and records what SemanticNavigator needs:
 * the navigator's events (way blocked, target blocked, end, error) and the
 * latest obstacle points with the pose they were sensed from. */
class NavInterfaceMonitor : public mrpt::nav::CRobot2NavInterface
{
public:
	/** Events received since the last takeEvents(). */
	struct Events
	{
		bool started = false;
		bool ended = false;
		bool waySeemsBlocked = false;
		bool targetBlocked = false;
		bool error = false;
		int apparentCollisions = 0;
		int waypointsReached = 0;
		bool any() const
		{
			return started || ended || waySeemsBlocked || targetBlocked ||
			       error || apparentCollisions || waypointsReached;
		}
	};

	explicit NavInterfaceMonitor(mrpt::nav::CRobot2NavInterface& robot);

	Events takeEvents();
	/** Latest obstacles (robot frame) and the robot pose when sensed. */
	const mrpt::maps::CSimplePointsMap& lastObstacles() const
	{
		return m_obstacles;
	}
	const mrpt::math::TPose2D& lastObstaclesPose() const
	{
		return m_obstaclesPose;
	}
	bool hasObstacles() const { return m_hasObstacles; }
	mrpt::nav::CRobot2NavInterface& robot() { return m_robot; }

	// ---- forwarded ------------------------------------------------------
	bool getCurrentPoseAndSpeeds(
	    mrpt::math::TPose2D& curPose, mrpt::math::TTwist2D& curVelGlobal,
	    mrpt::system::TTimeStamp& timestamp, mrpt::math::TPose2D& curOdometry,
	    std::string& frameId) override;
	bool changeSpeeds(const mrpt::kinematics::CVehicleVelCmd& cmd) override;
	bool changeSpeedsNOP() override;
	bool stop(bool isEmergencyStop) override;
	mrpt::kinematics::CVehicleVelCmd::Ptr getEmergencyStopCmd() override;
	mrpt::kinematics::CVehicleVelCmd::Ptr getStopCmd() override;
	mrpt::kinematics::CVehicleVelCmd::Ptr getAlignCmd(
	    const double relativeHeading) override;
	bool startWatchdog(float periodMs) override;
	bool stopWatchdog() override;
	bool senseObstacles(
	    mrpt::maps::CSimplePointsMap& obstacles,
	    mrpt::system::TTimeStamp& timestamp) override;
	void sendNavigationStartEvent() override;
	void sendNavigationEndEvent() override;
	void sendWaypointReachedEvent(int index, bool reachedNotSkipped) override;
	void sendNewWaypointTargetEvent(int index) override;
	void sendNavigationEndDueToErrorEvent() override;
	void sendWaySeemsBlockedEvent() override;
	void sendApparentCollisionEvent() override;
	void sendCannotGetCloserToBlockedTargetEvent() override;
	double getNavigationTime() override;
	void resetNavigationTimer() override;

private:
	mrpt::nav::CRobot2NavInterface& m_robot;
	std::mutex m_mutex;
	Events m_events;
	mrpt::maps::CSimplePointsMap m_obstacles;
	mrpt::math::TPose2D m_obstaclesPose;
	bool m_hasObstacles = false;
};

}  // namespace semnav
