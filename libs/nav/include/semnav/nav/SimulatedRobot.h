/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/core/Clock.h>
#include <mrpt/kinematics/CVehicleSimul_DiffDriven.h>
#include <mrpt/math/TPose2D.h>
#include <mrpt/nav/reactive/CRobot2NavInterfaceForSimulator.h>
#include <semnav/sim/RayCaster.h>
#include <semnav/sim/Scene.h>

#include <cstdint>
#include <random>
#include <vector>

namespace semnav
{
namespace detail
{
/** Holds the vehicle so it is built before the interface that refers to
 * it (base-from-member). */
struct DiffDriveVehicleHolder
{
	mrpt::kinematics::CVehicleSimul_DiffDriven m_vehicle;
};
}  // namespace detail

/** A simulated differential-drive robot in a scene:
 * MRPT's CVehicleSimul_DiffDriven behind
 * CRobot2NavInterfaceForSimulator_DiffDriven.
 *
 * - Obstacles are sensed by ray-casting a horizontal scan (one plane per
 *   scan height, from the robot centre) in the scene itself, not in the map:
 *   the map may be wrong.
 * - Collisions are checked after every step against the scene geometry: the
 *   robot is a vertical cylinder of robot_radius_m; rays along its radius
 *   at each collision height test it. A step that would collide is undone
 *   (the robot stops at the obstacle) and counted once per contact.
 * - Time is simulated: simulate(dt) advances it and, while the robot
 *   exists, MRPT's clock (mrpt::Clock, Simulated source) follows it, so the
 *   navigator's timeouts and timestamps run on simulated time. The previous
 *   clock source is restored by the destructor.
 * - Odometry is integrated by the robot itself from the true motion of each
 *   step; setOdometryNoise() adds a scene's odometry errors (heading bias
 *   and noise per metre, translation noise) to it.
 * - The pose the navigator sees (getCurrentPoseAndSpeeds) is the true pose,
 *   until setPoseEstimate() is called: from then on it is that map-frame
 *   estimate composed with the odometry since, as a localized real robot
 *   would report. Sensing and collisions always use the true pose. */
class SimulatedRobot
    : private detail::DiffDriveVehicleHolder,
      public mrpt::nav::CRobot2NavInterfaceForSimulator_DiffDriven
{
public:
	/** Options, INI section [SimulatedRobot] (config/navigation.ini). */
	struct TOptions : public mrpt::config::CLoadableOptions
	{
		void loadFromConfigFile(
		    const mrpt::config::CConfigFileBase& c,
		    const std::string& section) override;
		void saveToConfigFile(
		    mrpt::config::CConfigFileBase& c,
		    const std::string& section) const override;

		/** robot_radius_m: the robot's disc. */
		double robotRadius = 0.25;
		/** scan_heights_m: heights of the horizontal scan planes. */
		std::vector<double> scanHeights{0.15, 0.75};
		/** scan_fov_deg: field of view, centred ahead. */
		double scanFovDeg = 360;
		/** scan_beams: beams per plane. */
		int scanBeams = 240;
		/** scan_max_range_m. */
		double scanMaxRange = 5.0;
		/** collision_heights_m: heights at which contact is tested. */
		std::vector<double> collisionHeights{0.1, 0.35, 0.6, 0.9};
		/** collision_rays: rays around the disc per height. */
		int collisionRays = 72;
		/** time_step_s: simulation (and navigation) period. */
		double timeStep = 0.1;
		/** max_time_s: a run gives up after this much simulated time. */
		double maxTime = 300;
	};

	SimulatedRobot(
	    const Scene& scene, const TOptions& options,
	    const mrpt::math::TPose2D& start);
	~SimulatedRobot() override;
	SimulatedRobot(const SimulatedRobot&) = delete;
	SimulatedRobot& operator=(const SimulatedRobot&) = delete;

	/** Advances the simulation by dt seconds (collision check included). */
	void simulate(double dt);
	/** simulate(options().timeStep). */
	void simulate() { simulate(m_options.timeStep); }

	/** Reports the true pose, or after setPoseEstimate() the estimate
	 * (velocity rotated into its heading); odometry = odometry(). */
	bool getCurrentPoseAndSpeeds(
	    mrpt::math::TPose2D& curPose, mrpt::math::TTwist2D& curVel,
	    mrpt::system::TTimeStamp& timestamp, mrpt::math::TPose2D& curOdometry,
	    std::string& frameId) override;

	/** From now on the odometry of every step gets the errors of `spec`
	 * (per metre travelled in the step: heading bias, heading noise with
	 * std rotNoisePerM * sqrt(d / 1 m), translation noise likewise), drawn
	 * from a generator seeded with `seed`. */
	void setOdometryNoise(const OdometrySpec& spec, uint64_t seed);
	/** Integrated odometry (starts at the start pose). */
	const mrpt::math::TPose2D& odometry() const { return m_odometry; }
	/** Odometry distance travelled so far (m). */
	double odometryDistance() const { return m_odometryDistance; }
	/** The robot now believes it is at `mapPose` (e.g. a localizer's
	 * estimate); the reported pose follows it with the odometry. */
	void setPoseEstimate(const mrpt::math::TPose2D& mapPose);
	/** True once setPoseEstimate() was called. */
	bool reportsEstimate() const { return m_reportEstimate; }
	/** The pose the navigator sees: the estimate (see setPoseEstimate) or
	 * the true pose. */
	mrpt::math::TPose2D estimatedPose() const;
	/** estimatedPose() after every step since the first setPoseEstimate()
	 * (a jump where a later call corrects it). */
	const std::vector<mrpt::math::TPose2D>& estimatedTrajectory() const
	{
		return m_estimatedTrajectory;
	}

	/** Turns on the spot by `angle` (rad, by odometry) at `speed` rad/s in
	 * simulated time, then stops. */
	void turnInPlace(double angle, double speed);
	/** Commands zero velocity and lets one time step pass. */
	void stopNow();

	bool senseObstacles(
	    mrpt::maps::CSimplePointsMap& obstacles,
	    mrpt::system::TTimeStamp& timestamp) override;

	/** Turn on the spot toward a relative heading (45 deg/s, slower in
	 * the last 20 deg). */
	mrpt::kinematics::CVehicleVelCmd::Ptr getAlignCmd(
	    const double relativeHeading) override;

	/** True when the robot's cylinder at `pose` touches the scene. */
	bool inCollision(const mrpt::math::TPose2D& pose) const;

	const mrpt::math::TPose2D& pose() const
	{
		return m_vehicle.getCurrentGTPose();
	}
	double simTime() const { return m_vehicle.getTime(); }
	/** Contacts with the scene (a contact lasting several steps counts
	 * once). */
	int collisions() const { return m_collisions; }
	/** Where contacts happened. */
	const std::vector<mrpt::math::TPose2D>& collisionPoses() const
	{
		return m_collisionPoses;
	}
	/** True pose after every step, the start included. */
	const std::vector<mrpt::math::TPose2D>& trajectory() const
	{
		return m_trajectory;
	}
	const TOptions& options() const { return m_options; }
	const RayCaster& caster() const { return m_caster; }
	mrpt::kinematics::CVehicleSimul_DiffDriven& vehicle() { return m_vehicle; }

	/** Simulated time t as an MRPT timestamp (t = 0 at 2020-01-01). */
	static mrpt::Clock::time_point timestampOf(double t);

private:
	TOptions m_options;
	RayCaster m_caster;
	int m_collisions = 0;
	bool m_inContact = false;
	std::vector<mrpt::math::TPose2D> m_trajectory;
	std::vector<mrpt::math::TPose2D> m_collisionPoses;
	mrpt::Clock::Source m_previousClock;
	mrpt::math::TPose2D m_odometry;
	double m_odometryDistance = 0;
	bool m_odometryNoise = false;
	OdometrySpec m_odometrySpec;
	std::mt19937_64 m_rng;
	bool m_reportEstimate = false;
	/** Map pose of the odometry frame (estimate = m_odoToMap + odometry). */
	mrpt::math::TPose2D m_odoToMap;
	std::vector<mrpt::math::TPose2D> m_estimatedTrajectory;
};

}  // namespace semnav
