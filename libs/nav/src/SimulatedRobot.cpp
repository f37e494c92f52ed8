/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/kinematics/CVehicleVelCmd_DiffDriven.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt/poses/CPose2D.h>
#include <semnav/common/Error.h>
#include <semnav/common/OptionTable.h>
#include <semnav/nav/SimulatedRobot.h>

#include <cmath>
#include <sstream>

namespace semnav
{
namespace
{
using O = SimulatedRobot::TOptions;
const OptionTable<O>& optionTable()
{
	static const auto t =
	    OptionTable<O>()
	        .real(
	            "robot_radius_m", &O::robotRadius, 0.05, 5,
	            "Radius of the simulated robot's disc.")
	        .reals(
	            "scan_heights_m", &O::scanHeights, 0.0, 10,
	            "Heights of the horizontal obstacle scans.")
	        .real(
	            "scan_fov_deg", &O::scanFovDeg, 1, 360,
	            "Field of view of each scan.")
	        .integer("scan_beams", &O::scanBeams, 2, 100000, "Beams per scan.")
	        .real("scan_max_range_m", &O::scanMaxRange, 0.1, 100, "Scan range.")
	        .reals(
	            "collision_heights_m", &O::collisionHeights, 0.0, 10,
	            "Heights at which the robot's disc is checked for "
	            "collisions.")
	        .integer(
	            "collision_rays", &O::collisionRays, 8, 100000,
	            "Rays around the disc per collision height.")
	        .real(
	            "time_step_s", &O::timeStep, 0.001, 10, "Simulation time step.")
	        .real(
	            "max_time_s", &O::maxTime, 0.1, 1e6,
	            "A navigation taking longer fails.");
	return t;
}

constexpr double kEpoch = 1577836800.0;  // 2020-01-01T00:00:00Z
}  // namespace

SEMNAV_OPTIONS_FROM_TABLE(SimulatedRobot::TOptions, optionTable())

mrpt::Clock::time_point SimulatedRobot::timestampOf(double t)
{
	return mrpt::Clock::fromDouble(kEpoch + t);
}

SimulatedRobot::SimulatedRobot(
    const Scene& scene, const TOptions& options,
    const mrpt::math::TPose2D& start)
    : mrpt::nav::CRobot2NavInterfaceForSimulator_DiffDriven(m_vehicle),
      m_options(options),
      m_caster(scene),
      m_previousClock(mrpt::Clock::getActiveClock()),
      m_odometry(start)
{
	setLoggerName("SimulatedRobot");
	m_vehicle.setCurrentGTPose(start);
	m_vehicle.setCurrentOdometricPose(start);
	mrpt::Clock::setSimulatedTime(timestampOf(0));
	mrpt::Clock::setActiveClock(mrpt::Clock::Simulated);
	resetNavigationTimer();
	m_trajectory.push_back(start);
	if (inCollision(start))
	{
		m_collisions = 1;
		m_inContact = true;
		m_collisionPoses.push_back(start);
	}
}

SimulatedRobot::~SimulatedRobot()
{
	mrpt::Clock::setActiveClock(m_previousClock);
}

void SimulatedRobot::simulate(double dt)
{
	const mrpt::math::TPose2D before = m_vehicle.getCurrentGTPose();
	const mrpt::math::TPose2D odoBefore = m_vehicle.getCurrentOdometricPose();
	m_vehicle.simulateOneTimeStep(dt);
	mrpt::Clock::setSimulatedTime(timestampOf(m_vehicle.getTime()));
	const mrpt::math::TPose2D after = m_vehicle.getCurrentGTPose();
	if (inCollision(after))
	{
		if (!m_inContact)
		{
			m_collisions++;
			m_collisionPoses.push_back(after);
			MRPT_LOG_WARN_FMT(
			    "collision at (%.2f, %.2f), t = %.1f s", after.x, after.y,
			    m_vehicle.getTime());
		}
		m_inContact = true;
		// The obstacle stops the robot: undo the step.
		m_vehicle.setCurrentGTPose(before);
		m_vehicle.setCurrentOdometricPose(odoBefore);
	}
	else
		m_inContact = false;
	m_trajectory.push_back(m_vehicle.getCurrentGTPose());

	// Odometry: the true motion of the step, in the robot frame, with the
	// odometry errors.
	mrpt::poses::CPose2D delta =
	    mrpt::poses::CPose2D(m_vehicle.getCurrentGTPose()) -
	    mrpt::poses::CPose2D(before);
	const double d = delta.norm();
	if (m_odometryNoise && d > 0)
	{
		std::normal_distribution<double> n01(0.0, 1.0);
		const double s = std::sqrt(d);
		const double dt = m_odometrySpec.transNoise * s * n01(m_rng);
		const double k = (d + dt) / d;
		delta = mrpt::poses::CPose2D(
		    delta.x() * k, delta.y() * k,
		    delta.phi() + m_odometrySpec.rotBiasPerM * d +
		        m_odometrySpec.rotNoisePerM * s * n01(m_rng));
	}
	m_odometryDistance += d;
	m_odometry = (mrpt::poses::CPose2D(m_odometry) + delta).asTPose();
	m_odometry.phi = mrpt::math::wrapToPi(m_odometry.phi);
	if (m_reportEstimate) m_estimatedTrajectory.push_back(estimatedPose());
}

void SimulatedRobot::setOdometryNoise(const OdometrySpec& spec, uint64_t seed)
{
	m_odometrySpec = spec;
	m_odometryNoise = true;
	m_rng.seed(seed);
}

void SimulatedRobot::setPoseEstimate(const mrpt::math::TPose2D& mapPose)
{
	// m_odoToMap + odometry = mapPose
	m_odoToMap =
	    (mrpt::poses::CPose2D(mapPose) + (-mrpt::poses::CPose2D(m_odometry)))
	        .asTPose();
	m_reportEstimate = true;
	m_estimatedTrajectory.push_back(estimatedPose());
}

mrpt::math::TPose2D SimulatedRobot::estimatedPose() const
{
	if (!m_reportEstimate) return m_vehicle.getCurrentGTPose();
	auto p =
	    (mrpt::poses::CPose2D(m_odoToMap) + mrpt::poses::CPose2D(m_odometry))
	        .asTPose();
	p.phi = mrpt::math::wrapToPi(p.phi);
	return p;
}

bool SimulatedRobot::getCurrentPoseAndSpeeds(
    mrpt::math::TPose2D& curPose, mrpt::math::TTwist2D& curVel,
    mrpt::system::TTimeStamp& timestamp, mrpt::math::TPose2D& curOdometry,
    std::string& frameId)
{
	curPose = estimatedPose();
	// Velocity in the frame of the reported pose: the robot-frame twist
	// rotated by the reported heading.
	curVel = m_vehicle.getCurrentGTVelLocal();
	curVel.rotate(curPose.phi);
	timestamp = timestampOf(m_vehicle.getTime());
	curOdometry = m_odometry;
	frameId = "map";
	return true;
}

void SimulatedRobot::turnInPlace(double angle, double speed)
{
	const double dt = m_options.timeStep;
	double turned = 0;
	for (int guard = 0; guard < 100000; guard++)
	{
		const double left = std::abs(angle) - std::abs(turned);
		if (left <= 1e-3) break;
		mrpt::kinematics::CVehicleVelCmd_DiffDriven cmd;
		cmd.lin_vel = 0;
		cmd.ang_vel = (angle >= 0 ? 1 : -1) * std::min(speed, left / dt);
		m_vehicle.sendVelCmd(cmd);
		const double before = m_odometry.phi;
		simulate(dt);
		turned += mrpt::math::wrapToPi(m_odometry.phi - before);
	}
	stopNow();
}

void SimulatedRobot::stopNow()
{
	mrpt::kinematics::CVehicleVelCmd_DiffDriven cmd;
	cmd.lin_vel = 0;
	cmd.ang_vel = 0;
	m_vehicle.sendVelCmd(cmd);
	simulate(m_options.timeStep);
}

mrpt::kinematics::CVehicleVelCmd::Ptr SimulatedRobot::getAlignCmd(
    const double relativeHeading)
{
	auto cmd = std::make_shared<mrpt::kinematics::CVehicleVelCmd_DiffDriven>();
	cmd->lin_vel = 0;
	const double w = std::min(
	    45.0, std::max(10.0, std::abs(relativeHeading) * 180 / M_PI * 2.25));
	cmd->ang_vel = (relativeHeading >= 0 ? 1 : -1) * w * M_PI / 180;
	return cmd;
}

bool SimulatedRobot::inCollision(const mrpt::math::TPose2D& p) const
{
	const double R = m_options.robotRadius;
	const int n = m_options.collisionRays;
	for (double h : m_options.collisionHeights)
		for (int k = 0; k < n; k++)
		{
			const double a = 2 * M_PI * k / n;
			const mrpt::math::TPoint3D d{std::cos(a), std::sin(a), 0};
			const mrpt::math::TPoint3D c{p.x, p.y, h};
			// Outward from the centre, and inward from the rim (catches a
			// solid holding the centre).
			if (m_caster.cast(c, d, R).hit) return true;
			const mrpt::math::TPoint3D rim{c.x + R * d.x, c.y + R * d.y, h};
			if (m_caster.cast(rim, {-d.x, -d.y, 0}, R).hit) return true;
		}
	return false;
}

bool SimulatedRobot::senseObstacles(
    mrpt::maps::CSimplePointsMap& obstacles,
    mrpt::system::TTimeStamp& timestamp)
{
	obstacles.clear();
	timestamp = timestampOf(m_vehicle.getTime());
	const mrpt::math::TPose2D p = m_vehicle.getCurrentGTPose();
	const double fov = m_options.scanFovDeg * M_PI / 180;
	const int n = m_options.scanBeams;
	const bool full = m_options.scanFovDeg >= 360;
	for (double h : m_options.scanHeights)
		for (int k = 0; k < n; k++)
		{
			const double rel =
			    full ? 2 * M_PI * k / n : -fov / 2 + fov * k / (n - 1);
			const double a = p.phi + rel;
			const RayHit hit = m_caster.cast(
			    {p.x, p.y, h}, {std::cos(a), std::sin(a), 0},
			    m_options.scanMaxRange);
			if (!hit.hit) continue;
			obstacles.insertPoint(
			    static_cast<float>(hit.range * std::cos(rel)),
			    static_cast<float>(hit.range * std::sin(rel)),
			    static_cast<float>(h));
		}
	return true;
}

}  // namespace semnav
