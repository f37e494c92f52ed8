/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CConfigFileMemory.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/nav/RobotNavInterface.h>
#include <semnav/nav/SemanticNavigator.h>
#include <semnav/nav/StopAndScanLocalizer.h>
#include <semnav/nav/ViewPlanner.h>
#include <semnav/planning/CnnPlanner.h>
#include <semnav/planning/TraversabilityBuilder.h>
#include <semnav/robot/SweepObstacles.h>

#include <memory>
#include <string>
#include <vector>

namespace semnav
{
/** Everything the runtime's navigation is configured with:
 * config/navigation.ini ([SemanticNavigator], [StopAndScan],
 * [ViewPlanner], [RobotNavInterface], [SweepObstacles] and MRPT's
 * reactive-navigation sections, based on MRPT's reactive2d_config.ini) and
 * config/planning.ini
 * ([CnnPlanner], [Traversability], optionally [SemanticMap], [TravelCost]
 * for loading maps). The robot's own sections (e.g. the simulator's
 * [SimulatedRobot], see SimulationConfig) are loaded by whoever owns them
 * through `extra`.
 *
 * Sections other than these are errors; keys of semnav's sections are
 * checked by their TOptions; keys of MRPT's sections are checked against
 * what MRPT's navigator itself writes back (saveConfigFile), so a typo is an
 * error instead of a silently ignored key. */
struct NavigationConfig
{
	SemanticNavigator::TOptions navigator;
	StopAndScanLocalizer::TOptions stopAndScan;
	ViewPlanner::TOptions viewPlanner;
	RobotNavInterface::TOptions robotInterface;
	SweepObstacles::TOptions sweepObstacles;
	CnnPlanner::TOptions cnn;
	TraversabilityBuilder::TOptions traversability;
	SemanticMap::TOptions map;
	/** MRPT's sections, as read (shared: MRPT's CConfigFileMemory must not
	 * be copied). */
	std::shared_ptr<const mrpt::config::CConfigFileMemory> mrptSections;

	/** The cost profile of the navigation plans ([SemanticNavigator]
	 * profile; "planning": the [Traversability] one). */
	CostProfile navigationProfile() const;
	/** The traversability the navigator plans on, for `map`. */
	TraversabilityGrid navigationTraversability(const SemanticMap& map) const;
	/** Sections of navigation.ini that belong to MRPT. */
	static const std::vector<std::string>& mrptSectionNames();

	/** A section of navigation.ini loaded by another layer. */
	struct ExtraSection
	{
		std::string name;
		mrpt::config::CLoadableOptions* options = nullptr;
	};

	/** Loads navigation.ini (with the `extra` sections) and (if not empty)
	 * planning.ini. Throws ConfigError naming file, section and key. */
	static NavigationConfig load(
	    const std::string& navigationIni, const std::string& planningIni,
	    const std::vector<ExtraSection>& extra = {});
};

}  // namespace semnav
