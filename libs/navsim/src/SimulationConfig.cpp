/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/config/CConfigFile.h>
#include <semnav/common/ConfigChecks.h>
#include <semnav/common/Error.h>
#include <semnav/navsim/SimulationConfig.h>

namespace semnav
{
double SimulationConfig::arrivalTolerance(bool objectGoal) const
{
	const double reach = objectGoal ? TraversabilityBuilder(traversability)
	                                      .goalRegionRadius(navigationProfile())
	                                : traversability.goalReach;
	return reach + navigator.goalAllowedDistance + arrivalMargin;
}

SimulationConfig SimulationConfig::load(
    const std::string& navigationIni, const std::string& planningIni,
    const std::string& simIni)
{
	SimulationConfig c;
	static_cast<NavigationConfig&>(c) =
	    NavigationConfig::load(navigationIni, planningIni);
	if (simIni.empty()) return c;
	const auto ini = openIniFile(simIni, {"Simulator", "SimulatedRobot"});
	try
	{
		c.robot.loadFromConfigFile(*ini, "SimulatedRobot");
	}
	catch (const ConfigError& e)
	{
		throw ConfigError(simIni + ": " + e.what());
	}
	return c;
}

}  // namespace semnav
