/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

namespace semnav
{
class RobotBase;
class SweepSource;
class ControlClock;
class LocalizedPose;
class PoseSource;

/** What semnav's runtime drives a robot through: its base, its sweeps,
 * the clock its control loop runs on and the pose it reports. A real robot
 * (semnav-robot) and the simulator (SimulatedRobot) fill the same four;
 * nothing on the robot's path sees anything else. */
struct RobotInterfaces
{
	RobotBase* base = nullptr;
	SweepSource* sweeps = nullptr;
	ControlClock* clock = nullptr;
	/** Set by the localizer; read by the navigator. */
	LocalizedPose* pose = nullptr;
	/** Ground truth for evaluation (a simulation, a motion-capture
	 * system); nullptr on a robot. Never used to steer. */
	const PoseSource* truth = nullptr;
};

}  // namespace semnav
