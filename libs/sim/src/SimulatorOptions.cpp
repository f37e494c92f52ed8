/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/config/CConfigFileBase.h>
#include <semnav/common/ConfigChecks.h>
#include <semnav/common/Error.h>
#include <semnav/sim/SimulatorOptions.h>

#include <cmath>
#include <cstdio>

namespace semnav
{
const std::vector<std::string>& SimulatorOptions::knownKeys()
{
	static const std::vector<std::string> keys{
	    "sensor_label",          "line_period_s",        "robot_speed_mps",
	    "robot_turn_rate_deg_s", "terrain_cell_m",       "threads",
	    "brute_force_raycast",   "rawlog_compress_level"};
	return keys;
}

void SimulatorOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& c, const std::string& s)
{
	checkKnownKeys(c, s, knownKeys());
	SimulatorOptions o = *this;  // assign only when everything is valid
	o.sensorLabel = c.read_string(s, "sensor_label", sensorLabel, false);
	if (o.sensorLabel.empty() ||
	    o.sensorLabel.find_first_of(" \t\r\n") != std::string::npos)
		throw ConfigError(
		    "[" + s + "] sensor_label = '" + o.sensorLabel +
		    "' must be a non-empty word without spaces");
	o.linePeriod = readChecked(c, s, "line_period_s", linePeriod, 1e-4, 10.0);
	o.robotSpeed = readChecked(c, s, "robot_speed_mps", robotSpeed, 0.01, 10.0);
	o.robotTurnRate = readChecked(
	                      c, s, "robot_turn_rate_deg_s",
	                      robotTurnRate * 180.0 / M_PI, 1.0, 3600.0) *
	                  M_PI / 180.0;
	o.terrainCell = readChecked(c, s, "terrain_cell_m", terrainCell, 0.01, 1.0);
	o.threads = readCheckedInt(c, s, "threads", threads, 0, 1024);
	o.bruteForce = readCheckedBool(c, s, "brute_force_raycast", bruteForce);
	o.compressLevel =
	    readCheckedInt(c, s, "rawlog_compress_level", compressLevel, 0, 9);
	*this = o;
}

namespace
{
/** Numbers with enough digits to read back the same value. */
std::string num(double v)
{
	char buf[64];
	std::snprintf(buf, sizeof(buf), "%.12g", v);
	return buf;
}
}  // namespace

void SimulatorOptions::saveToConfigFile(
    mrpt::config::CConfigFileBase& c, const std::string& s) const
{
	c.write(s, "sensor_label", sensorLabel);
	c.write(s, "line_period_s", num(linePeriod));
	c.write(s, "robot_speed_mps", num(robotSpeed));
	c.write(s, "robot_turn_rate_deg_s", num(robotTurnRate * 180.0 / M_PI));
	c.write(s, "terrain_cell_m", num(terrainCell));
	c.write(s, "threads", std::to_string(threads));
	writeBool(c, s, "brute_force_raycast", bruteForce);
	c.write(s, "rawlog_compress_level", std::to_string(compressLevel));
}

}  // namespace semnav
