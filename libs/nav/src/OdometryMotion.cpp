/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/math/wrap2pi.h>
#include <mrpt/poses/CPose2D.h>
#include <semnav/nav/NavigationErrors.h>
#include <semnav/nav/OdometryMotion.h>
#include <semnav/robot/ControlClock.h>
#include <semnav/robot/RobotBase.h>

#include <algorithm>
#include <cmath>

namespace semnav
{
namespace
{
/** Waypoints closer than this are reached. */
constexpr double kReached = 0.05;
/** Farther off the bearing than this, the base turns on the spot first. */
const double kTurnFirst = mrpt::DEG2RAD(20.0);
/** Spacing of the waypoints taken from a path (m). */
constexpr double kSpacing = 0.3;
}  // namespace

void OdometryMotion::command(double v, double w)
{
	if (!m_robot.base->setVelocity(v, w))
		throw LocalizationFailedError(
		    "localization: the base refused to move (emergency stop?)");
	m_robot.clock->waitFor(m_robot.clock->period());
}

void OdometryMotion::turn(double angle)
{
	const double dt = m_robot.clock->period();
	double turned = 0;
	for (int guard = 0; guard < 100000; guard++)
	{
		const double left = std::abs(angle) - std::abs(turned);
		if (left <= 1e-3) break;
		const double before = m_robot.base->odometry().pose.phi;
		command(0, (angle >= 0 ? 1 : -1) * std::min(m_turnSpeed, left / dt));
		turned +=
		    mrpt::math::wrapToPi(m_robot.base->odometry().pose.phi - before);
	}
	m_robot.base->stop();
	m_robot.clock->tick();
}

double OdometryMotion::follow(
    const std::vector<mrpt::math::TPoint2D>& path, double heading)
{
	const double dt = m_robot.clock->period();
	const mrpt::poses::CPose2D start(m_robot.base->odometry().pose);
	double length = 0;
	mrpt::poses::CPose2D last = start;
	// Waypoints every kSpacing along the path, and its end.
	std::vector<mrpt::math::TPoint2D> targets;
	for (std::size_t i = 0; i < path.size(); i++)
		if (i + 1 == path.size() ||
		    (targets.empty() ? std::hypot(path[i].x, path[i].y)
		                     : std::hypot(
		                           path[i].x - targets.back().x,
		                           path[i].y - targets.back().y)) >= kSpacing)
			targets.push_back(path[i]);
	for (const auto& q : targets)
	{
		double tx, ty;
		start.composePoint(q.x, q.y, tx, ty);
		const double far = std::hypot(tx - last.x(), ty - last.y());
		const int steps = static_cast<int>(
		    10 * (far / m_speed + 2 * M_PI / m_turnSpeed) / dt + 100);
		for (int k = 0; k < steps; k++)
		{
			const mrpt::poses::CPose2D now(m_robot.base->odometry().pose);
			double lx, ly;
			now.inverseComposePoint(tx, ty, lx, ly);
			const double d = std::hypot(lx, ly);
			if (d < kReached) break;
			if (k == steps - 1)
				throw LocalizationFailedError(
				    "localization: the base did not reach a waypoint of the "
				    "drive to look (odometry not moving?)");
			const double bearing = std::atan2(ly, lx);
			const double w = std::clamp(
			    std::abs(bearing) > kTurnFirst ? bearing / dt : 2 * bearing,
			    -m_turnSpeed, m_turnSpeed);
			const double v =
			    std::abs(bearing) > kTurnFirst ? 0 : std::min(m_speed, d / dt);
			command(v, w);
		}
		const mrpt::poses::CPose2D now(m_robot.base->odometry().pose);
		length += std::hypot(now.x() - last.x(), now.y() - last.y());
		last = now;
	}
	m_robot.base->stop();
	m_robot.clock->tick();
	turn(mrpt::math::wrapToPi(
	    start.phi() + heading - m_robot.base->odometry().pose.phi));
	return length;
}

}  // namespace semnav
