/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/math/TPoint2D.h>
#include <semnav/robot/RobotInterfaces.h>

#include <vector>

namespace semnav
{
/** Short moves of a base steered by its odometry alone: what a robot that
 * does not know where it is yet can do (turn between the sweeps of a start,
 * drive to a place to look from). One velocity command per control period
 * (RobotInterfaces::clock); the base is stopped at the end. Throws
 * LocalizationFailedError when the base refuses a command (emergency stop)
 * or a move does not end (a base that does not move). */
class OdometryMotion
{
public:
	/** `speed` m/s, `turnSpeed` rad/s. */
	OdometryMotion(const RobotInterfaces& robot, double speed, double turnSpeed)
	    : m_robot(robot), m_speed(speed), m_turnSpeed(turnSpeed)
	{
	}

	/** Turns on the spot by `angle` (rad, by odometry). */
	void turn(double angle);

	/** Drives along `path` (points in the robot's frame now, the first
	 * one where it stands), then turns to face `heading` (rad, same
	 * frame). Returns the odometry length driven (m). */
	double follow(
	    const std::vector<mrpt::math::TPoint2D>& path, double heading);

private:
	void command(double v, double w);

	RobotInterfaces m_robot;
	double m_speed, m_turnSpeed;
};

}  // namespace semnav
