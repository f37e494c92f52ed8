/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/math/TPose2D.h>
#include <semnav/robot/ControlClock.h>
#include <semnav/robot/LocalizedPose.h>
#include <semnav/robot/RobotInterfaces.h>
#include <semnav/sim/RayCastObstacles.h>
#include <semnav/sim/RayCaster.h>
#include <semnav/sim/Scene.h>
#include <semnav/sim/SimulatedBase.h>
#include <semnav/sim/SimulatedRobotOptions.h>
#include <semnav/sim/SimulatedSweepSource.h>

#include <vector>

namespace semnav
{
/** A whole simulated robot in a scene, plugged into the same seams as a
 * real one (interfaces()): a SimulatedBase, the simulated tilting laser
 * (SimulatedSweepSource), a ray-cast obstacle sensor (RayCastObstacles),
 * the simulated clock (this object: waitFor() advances the world) and the
 * pose it reports (a LocalizedPose; or the true pose, for runs where the
 * robot knows it: truePose()).
 *
 * It also keeps what only a simulation knows: the true pose as ground
 * truth (interfaces().truth) and the reported pose after every step once
 * it has an estimate (estimatedTrajectory()). */
class SimulatedRobot : public ControlClock
{
public:
	using TOptions = SimulatedRobotOptions;

	SimulatedRobot(
	    const Scene& scene, const TOptions& options,
	    const mrpt::math::TPose2D& start);
	SimulatedRobot(const SimulatedRobot&) = delete;
	SimulatedRobot& operator=(const SimulatedRobot&) = delete;

	/** The seams (base, sweeps, clock, pose; truth = the true pose). */
	RobotInterfaces interfaces();

	// ControlClock: simulated time; waitFor() simulates.
	double now() const override { return m_base.time(); }
	void waitFor(double seconds) override;
	double period() const override { return m_options.timeStep; }

	/** The scene's odometry errors from now on (seed + 7919), when
	 * odometry_noise is on. */
	void enableOdometryNoise(const OdometrySpec& spec);

	SimulatedBase& base() { return m_base; }
	const SimulatedBase& base() const { return m_base; }
	SimulatedSweepSource& sweeps() { return m_sweeps; }
	RayCastObstacles& obstacles() { return m_obstacles; }
	/** The pose the robot reports: the localizer's estimate composed with
	 * odometry (before any estimate: the odometry). */
	LocalizedPose& localizedPose() { return m_localized; }
	/** The true pose as a PoseSource. */
	const PoseSource& truePose() const { return m_truth; }
	/** Reported pose after every step since the first estimate (a jump
	 * where a later estimate corrects it). */
	const std::vector<mrpt::math::TPose2D>& estimatedTrajectory() const
	{
		return m_localized.trajectory;
	}
	const TOptions& options() const { return m_options; }

private:
	struct TruePose : public PoseSource
	{
		explicit TruePose(const SimulatedBase& b) : base(b) {}
		mrpt::math::TPose2D pose() const override { return base.pose(); }
		const SimulatedBase& base;
	};
	/** A LocalizedPose that records the reported pose. */
	struct RecordedPose : public LocalizedPose
	{
		using LocalizedPose::LocalizedPose;
		void setEstimate(
		    const mrpt::math::TPose2D& mapPose,
		    const mrpt::math::TPose2D& odometry) override;
		std::vector<mrpt::math::TPose2D> trajectory;
	};

	TOptions m_options;
	RayCaster m_caster;
	SimulatedBase m_base;
	RayCastObstacles m_obstacles;
	SimulatedSweepSource m_sweeps;
	RecordedPose m_localized;
	TruePose m_truth;
};

}  // namespace semnav
