/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CLoadableOptions.h>

#include <vector>

namespace semnav
{
/** Options of the simulated robot (SimulatedRobot and its parts), INI
 * section [SimulatedRobot] (config/navigation.ini). */
struct SimulatedRobotOptions : public mrpt::config::CLoadableOptions
{
	void loadFromConfigFile(
	    const mrpt::config::CConfigFileBase& c,
	    const std::string& section) override;
	void saveToConfigFile(
	    mrpt::config::CConfigFileBase& c,
	    const std::string& section) const override;

	/** robot_radius_m: the robot's disc. */
	double robotRadius = 0.25;
	/** scan_heights_m: heights of the horizontal obstacle scan planes. */
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
	/** watchdog_s: the base stops when no command came for this long. */
	double watchdog = 1.0;
	/** line_period_s: time of one scan line of the tilting laser; a sweep
	 * takes lines x period of simulated time. */
	double linePeriod = 1.0 / 75;
	/** odometry_noise: when the robot localizes itself, its odometry gets
	 * the scene's odometry errors (heading bias and noise). */
	bool odometryNoise = true;
	/** seed: laser range noise (seed) and odometry noise (seed + 7919). */
	int seed = 1;
};

}  // namespace semnav
