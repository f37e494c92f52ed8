/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/OptionTable.h>
#include <semnav/sim/SimulatedRobotOptions.h>

namespace semnav
{
namespace
{
using O = SimulatedRobotOptions;
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
	            "A navigation taking longer fails.")
	        .real(
	            "watchdog_s", &O::watchdog, 0.01, 100,
	            "The base stops when no command came for this long.")
	        .real(
	            "line_period_s", &O::linePeriod, 0, 10,
	            "Time of one scan line: a sweep stops the robot this long "
	            "per line.")
	        .flag(
	            "odometry_noise", &O::odometryNoise,
	            "Odometry gets the scene's odometry errors while "
	            "localizing.")
	        .integer(
	            "seed", &O::seed, 0, 1 << 30,
	            "Laser range noise and odometry noise.");
	return t;
}
}  // namespace

SEMNAV_OPTIONS_FROM_TABLE(SimulatedRobotOptions, optionTable())

}  // namespace semnav
