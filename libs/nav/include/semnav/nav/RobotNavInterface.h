/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/nav/reactive/CRobot2NavInterface.h>

namespace semnav
{
class RobotBase;
class PoseSource;
class ObstacleSource;
class ControlClock;

/** MRPT's CRobot2NavInterface over semnav's robot seams, built once for any
 * robot: velocity commands go to a RobotBase (changeSpeedsNOP() feeds its
 * watchdog), the pose is a PoseSource's (the localizer's estimate composed
 * with odometry) with the base's velocity, obstacles come from an
 * ObstacleSource (the latest sweep on a robot, a ray cast in the
 * simulator), and navigation time runs on the ControlClock.
 *
 * MRPT's stop(isEmergencyStop = true) is a navigation stop (MRPT sends it
 * on every navigation error) and maps to RobotBase::stop(); a safety stop
 * is RobotBase::emergencyStop(), which the owner calls.
 *
 * Options: INI section [RobotNavInterface] (config/navigation.ini). */
class RobotNavInterface : public mrpt::nav::CRobot2NavInterface
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

		/** align_gain, align_min_speed_deg_s, align_max_speed_deg_s: turn
		 * on the spot toward a heading error e at gain * e, clamped to
		 * [min, max] (deg/s). */
		double alignGain = 2.25;
		double alignMinSpeedDeg = 10;
		double alignMaxSpeedDeg = 45;
	};

	/** All four must outlive the interface. */
	RobotNavInterface(
	    RobotBase& base, const PoseSource& pose, ObstacleSource& obstacles,
	    const ControlClock& clock, const TOptions& options);

	bool getCurrentPoseAndSpeeds(
	    mrpt::math::TPose2D& curPose, mrpt::math::TTwist2D& curVel,
	    mrpt::system::TTimeStamp& timestamp, mrpt::math::TPose2D& curOdometry,
	    std::string& frameId) override;
	bool changeSpeeds(const mrpt::kinematics::CVehicleVelCmd& cmd) override;
	bool changeSpeedsNOP() override;
	bool stop(bool isEmergencyStop) override;
	mrpt::kinematics::CVehicleVelCmd::Ptr getStopCmd() override;
	mrpt::kinematics::CVehicleVelCmd::Ptr getEmergencyStopCmd() override;
	mrpt::kinematics::CVehicleVelCmd::Ptr getAlignCmd(
	    const double relativeHeading) override;
	bool senseObstacles(
	    mrpt::maps::CSimplePointsMap& obstacles,
	    mrpt::system::TTimeStamp& timestamp) override;
	double getNavigationTime() override;
	void resetNavigationTimer() override;

	const TOptions& options() const { return m_options; }

private:
	RobotBase& m_base;
	const PoseSource& m_pose;
	ObstacleSource& m_obstacles;
	const ControlClock& m_clock;
	TOptions m_options;
	double m_navigationStart = 0;
};

}  // namespace semnav
