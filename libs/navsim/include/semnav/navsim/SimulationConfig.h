/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/nav/NavigationConfig.h>
#include <semnav/sim/SimulatedRobot.h>

#include <string>

namespace semnav
{
/** The runtime's NavigationConfig (config/navigation.ini, planning.ini)
 * plus the simulated robot ([SimulatedRobot] of config/sim.ini). */
struct SimulationConfig : public NavigationConfig
{
	SimulatedRobot::TOptions robot;

	/** NavigationConfig::load(navigationIni, planningIni) and
	 * [SimulatedRobot] of `simIni` (when not empty; its [Simulator] is
	 * semnav-sim's). Throws ConfigError naming file, section and key. */
	static SimulationConfig load(
	    const std::string& navigationIni, const std::string& planningIni,
	    const std::string& simIni);
};

}  // namespace semnav
