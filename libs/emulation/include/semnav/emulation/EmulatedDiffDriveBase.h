/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/math/TPose2D.h>
#include <mrpt/math/TTwist2D.h>
#include <semnav/robot/RobotBase.h>
#include <semnav/sim/Scene.h>
#include <semnav/sim/SimulatedRobotOptions.h>

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

namespace semnav
{
class RayCaster;
class SimulatedBase;

/** The emulated robot's differential-drive base, in real time: a
 * SimulatedBase (MRPT's CVehicleSimul_DiffDriven, collisions against the
 * scene, odometry drifting as the scene's `odometry:` says) stepped by its
 * own thread every step_s of wall time. command() is a velocity command as
 * a real base receives it; with no command for watchdog_s the base stops
 * itself. truePose() moves the emulated laser. Thread-safe.
 *
 * The simulated base makes MRPT's clock simulated; this one gives it back
 * the previous (real-time) source, as the emulators run on wall time. */
class EmulatedDiffDriveBase
{
public:
	struct Options
	{
		/** Simulation step (s of wall time). */
		double step = 0.02;
		/** No command for this long: the base stops (s). */
		double watchdog = 0.3;
		/** Odometry errors of the scene's `odometry:`, seeded. */
		bool odometryNoise = true;
		uint64_t seed = 1;
		/** When set, one line per step: wall time (s since the epoch),
		 * true x y phi (m, rad), true v w (m/s, rad/s). */
		std::string trajectoryFile;
		/** The robot's disc and collision rays ([SimulatedRobot]). */
		SimulatedRobotOptions robot;
	};

	/** What the base knows of itself at one step. */
	struct State
	{
		mrpt::math::TPose2D truePose;
		/** True velocity in the robot frame. */
		mrpt::math::TTwist2D velocity;
		/** Odometry (drifting pose, true velocity, distance). */
		RobotBase::Odometry odometry;
		int collisions = 0;
		int watchdogStops = 0;
		std::size_t commands = 0;
		/** Seconds since start(). */
		double time = 0;
	};

	/** The base at `start` in `scene`. Throws IoError when the trajectory
	 * file cannot be written. */
	EmulatedDiffDriveBase(
	    const Scene& scene, const mrpt::math::TPose2D& start,
	    const Options& options);
	~EmulatedDiffDriveBase();
	EmulatedDiffDriveBase(const EmulatedDiffDriveBase&) = delete;
	EmulatedDiffDriveBase& operator=(const EmulatedDiffDriveBase&) = delete;

	/** Starts stepping in real time. */
	void start();
	/** Stops stepping (the robot stands still) and closes the file. */
	void stop();
	/** A velocity command (v m/s, w rad/s), as cmd_vel brings it. */
	void command(double v, double w);
	State state() const;
	mrpt::math::TPose2D truePose() const;
	const Options& options() const { return m_options; }

private:
	void run();

	Scene m_scene;
	Options m_options;
	std::unique_ptr<RayCaster> m_caster;
	std::unique_ptr<SimulatedBase> m_base;
	std::ofstream m_trajectory;
	mutable std::mutex m_mutex;
	std::size_t m_commands = 0;
	std::thread m_thread;
	std::atomic<bool> m_running{false};
};

}  // namespace semnav
