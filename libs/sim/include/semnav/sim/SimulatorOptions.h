/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CLoadableOptions.h>

#include <string>
#include <vector>

namespace semnav
{
/** Options of SimulationRunner, INI section [Simulator] (config/sim.ini).
 * Unknown keys and out-of-range values throw ConfigError. */
struct SimulatorOptions : public mrpt::config::CLoadableOptions
{
	/** sensor_label: sensorLabel of the scan lines (no spaces). */
	std::string sensorLabel = "TILT_LMS";
	/** line_period_s: time between scan lines (LMS200, 0.5 deg interlaced:
	 * 37.5 Hz). */
	double linePeriod = 1.0 / 37.5;
	/** robot_speed_mps: translation speed between stops. */
	double robotSpeed = 0.3;
	/** robot_turn_rate_deg_s: rotation speed between stops (stored in
	 * rad/s). */
	double robotTurnRate = 30.0 * M_PI / 180.0;
	/** terrain_cell_m: grid step of terrain height fields. */
	double terrainCell = 0.1;
	/** threads: OpenMP threads over scan lines, 0 = all cores. */
	int threads = 0;
	/** brute_force_raycast: test every primitive of every ray (slow;
	 * reference mode). */
	bool bruteForce = false;
	/** rawlog_compress_level: gzip level of the rawlog, 0..9. */
	int compressLevel = 1;

	/** Keys of section [Simulator]. */
	static const std::vector<std::string>& knownKeys();

	void loadFromConfigFile(
	    const mrpt::config::CConfigFileBase& source,
	    const std::string& section) override;
	void saveToConfigFile(
	    mrpt::config::CConfigFileBase& target,
	    const std::string& section) const override;
};

}  // namespace semnav
