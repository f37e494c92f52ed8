/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/kinematics/CVehicleVelCmd_DiffDriven.h>
#include <semnav/common/OptionTable.h>
#include <semnav/nav/RobotNavInterface.h>
#include <semnav/robot/ControlClock.h>
#include <semnav/robot/ObstacleSource.h>
#include <semnav/robot/PoseSource.h>
#include <semnav/robot/RobotBase.h>

#include <algorithm>
#include <cmath>

namespace semnav
{
namespace
{
using O = RobotNavInterface::TOptions;
const OptionTable<O>& optionTable()
{
	static const auto t =
	    OptionTable<O>()
	        .real(
	            "align_gain", &O::alignGain, 0.1, 100,
	            "Turning toward a heading: turn rate per heading error...")
	        .real(
	            "align_min_speed_deg_s", &O::alignMinSpeedDeg, 0.1, 360,
	            "...at least this...")
	        .real(
	            "align_max_speed_deg_s", &O::alignMaxSpeedDeg, 0.1, 360,
	            "...and at most this.");
	return t;
}

mrpt::kinematics::CVehicleVelCmd::Ptr diffDriveCommand(double v, double w)
{
	auto cmd = std::make_shared<mrpt::kinematics::CVehicleVelCmd_DiffDriven>();
	cmd->lin_vel = v;
	cmd->ang_vel = w;
	return cmd;
}
}  // namespace

SEMNAV_OPTIONS_FROM_TABLE(RobotNavInterface::TOptions, optionTable())

RobotNavInterface::RobotNavInterface(
    RobotBase& base, const PoseSource& pose, ObstacleSource& obstacles,
    const ControlClock& clock, const TOptions& options)
    : m_base(base),
      m_pose(pose),
      m_obstacles(obstacles),
      m_clock(clock),
      m_options(options)
{
	setLoggerName("RobotNavInterface");
	resetNavigationTimer();
}

bool RobotNavInterface::getCurrentPoseAndSpeeds(
    mrpt::math::TPose2D& curPose, mrpt::math::TTwist2D& curVel,
    mrpt::system::TTimeStamp& timestamp, mrpt::math::TPose2D& curOdometry,
    std::string& frameId)
{
	const RobotBase::Odometry odo = m_base.odometry();
	curPose = m_pose.pose();
	// The robot-frame twist in the frame of the reported pose.
	curVel = odo.velocity;
	curVel.rotate(curPose.phi);
	timestamp = odo.time;
	curOdometry = odo.pose;
	frameId = "map";
	return true;
}

bool RobotNavInterface::changeSpeeds(
    const mrpt::kinematics::CVehicleVelCmd& cmd)
{
	const auto* dd =
	    dynamic_cast<const mrpt::kinematics::CVehicleVelCmd_DiffDriven*>(&cmd);
	if (!dd)
	{
		MRPT_LOG_ERROR("not a differential-drive velocity command");
		return false;
	}
	return m_base.setVelocity(dd->lin_vel, dd->ang_vel);
}

bool RobotNavInterface::changeSpeedsNOP()
{
	m_base.keepAlive();
	return true;
}

bool RobotNavInterface::stop(bool /*isEmergencyStop*/)
{
	return m_base.stop();
}

mrpt::kinematics::CVehicleVelCmd::Ptr RobotNavInterface::getStopCmd()
{
	return diffDriveCommand(0, 0);
}

mrpt::kinematics::CVehicleVelCmd::Ptr RobotNavInterface::getEmergencyStopCmd()
{
	return getStopCmd();
}

mrpt::kinematics::CVehicleVelCmd::Ptr RobotNavInterface::getAlignCmd(
    const double relativeHeading)
{
	const double wDeg = std::min(
	    m_options.alignMaxSpeedDeg,
	    std::max(
	        m_options.alignMinSpeedDeg,
	        std::abs(relativeHeading) * 180 / M_PI * m_options.alignGain));
	return diffDriveCommand(
	    0, (relativeHeading >= 0 ? 1 : -1) * wDeg * M_PI / 180);
}

bool RobotNavInterface::senseObstacles(
    mrpt::maps::CSimplePointsMap& obstacles,
    mrpt::system::TTimeStamp& timestamp)
{
	return m_obstacles.sense(obstacles, timestamp);
}

double RobotNavInterface::getNavigationTime()
{
	return m_clock.now() - m_navigationStart;
}

void RobotNavInterface::resetNavigationTimer()
{
	m_navigationStart = m_clock.now();
}

}  // namespace semnav
