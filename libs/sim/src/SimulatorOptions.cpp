/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/config/CConfigFileBase.h>
#include <semnav/common/Error.h>
#include <semnav/common/OptionTable.h>
#include <semnav/sim/SimulatorOptions.h>

#include <cmath>
#include <cstdio>

namespace semnav
{
namespace
{
using O = SimulatorOptions;
const OptionTable<O>& optionTable()
{
	static const auto t =
	    OptionTable<O>()
	        .text(
	            "sensor_label", &O::sensorLabel,
	            "sensorLabel of the simulated laser's observations.")
	        .check(
	            [](const O& o)
	            {
		            return !o.sensorLabel.empty() &&
		                   o.sensorLabel.find_first_of(" \t\r\n") ==
		                       std::string::npos;
	            },
	            "sensor_label must be a non-empty word without spaces")
	        .real(
	            "line_period_s", &O::linePeriod, 1e-4, 10.0,
	            "Time of one scan line.")
	        .real(
	            "robot_speed_mps", &O::robotSpeed, 0.01, 10.0,
	            "Speed of the robot between sweeps.")
	        .angle(
	            "robot_turn_rate_deg_s", &O::robotTurnRate, 1.0, 3600.0,
	            "Turn rate of the robot between sweeps.")
	        .real(
	            "terrain_cell_m", &O::terrainCell, 0.01, 1.0,
	            "Cell size of the terrain height field.")
	        .integer(
	            "threads", &O::threads, 0, 1024,
	            "Ray casting threads; 0 = all cores.")
	        .flag(
	            "brute_force_raycast", &O::bruteForce,
	            "Cast every ray against every shape (reference).")
	        .integer(
	            "rawlog_compress_level", &O::compressLevel, 0, 9,
	            "gzip level of the rawlog written.");
	return t;
}
}  // namespace

const std::vector<std::string>& SimulatorOptions::knownKeys()
{
	static const std::vector<std::string> keys = optionTable().keys();
	return keys;
}

SEMNAV_OPTIONS_FROM_TABLE(SimulatorOptions, optionTable())

namespace
{
/** Numbers with enough digits to read back the same value. */
}  // namespace

}  // namespace semnav
