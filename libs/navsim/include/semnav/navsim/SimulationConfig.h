/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/nav/NavigationConfig.h>
#include <semnav/planning/TraversabilityBuilder.h>
#include <semnav/sim/SimulatedRobot.h>

#include <string>

namespace semnav
{
/** The runtime's NavigationConfig (config/navigation.ini, planning.ini)
 * plus the simulated robot ([SimulatedRobot] of config/sim.ini). */
struct SimulationConfig : public NavigationConfig
{
	SimulatedRobot::TOptions robot;
	/** A believed arrival is true when the robot truly stands within
	 * arrivalTolerance() of the goal; this margin (m) covers the map's
	 * error in the object's footprint (semnav-nav --arrival-margin). */
	double arrivalMargin = 0.3;

	/** Farthest true distance (m) from the goal that counts as arrived:
	 * the goal region's reach (an object's footprint:
	 * TraversabilityBuilder::goalRegionRadius() of the navigation profile;
	 * a point: goal_reach_m) + MRPT's goal_allowed_distance_m +
	 * arrivalMargin. */
	double arrivalTolerance(bool objectGoal) const;

	/** NavigationConfig::load(navigationIni, planningIni) and
	 * [SimulatedRobot] of `simIni` (when not empty; its [Simulator] is
	 * semnav-sim's). Throws ConfigError naming file, section and key. */
	static SimulationConfig load(
	    const std::string& navigationIni, const std::string& planningIni,
	    const std::string& simIni);
};

}  // namespace semnav
