/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/localization/MappingLocalizer.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/nav/StopAndScanLocalizer.h>
#include <semnav/navsim/SimulatedNavigation.h>
#include <semnav/navsim/SimulationConfig.h>
#include <semnav/perception/PerceptionPipeline.h>
#include <semnav/sim/Scene.h>

#include <optional>
#include <string>
#include <vector>

namespace semnav
{
/** A semnav-nav run: the semantic map (a map directory, or a scene's
 * ground truth), the scene the robot drives in, optionally the robot's own
 * stop-and-scan localization, then one command through SimulatedNavigation,
 * with the navigation log and the picture written to an output directory. */
class NavigationRun
{
public:
	/** What a run is made of. */
	struct Settings
	{
		SimulationConfig config;
		/** The scene the robot drives in (YAML). */
		std::string scene;
		/** The map: a semnav-map directory, else the ground truth of the
		 * scene file `gtMapScene`. */
		std::string mapDir, gtMapScene;
		/** Labels whose scene objects are added to a map that lacks them
		 * (ground truth standing in for the detector). */
		std::vector<std::string> instancesFromScene;
		/** The robot localizes itself (nothing: it knows its pose). */
		std::optional<StopAndScanLocalizer::Mode> localize;
		std::optional<mrpt::math::TPose2D> startGuess;
		/** Carry the robot to `kidnapTo` at simulated time `kidnapAt`. */
		std::optional<double> kidnapAt;
		mrpt::math::TPose2D kidnapTo;
		MappingLocalizer::TOptions localization;
		PerceptionPipeline::TOptions perception;
		/** Object detection in the localizer's sweeps (none without). */
		std::optional<CascadeDetector::TOptions> cascades;
		/** Output directory for navigation.reactivenavlog and
		 * navigation.png ("" for none). */
		std::string outDir;
		/** Localization progress (each sweep, each drive to look) on
		 * stderr. */
		bool verbose = false;
	};

	/** An instance of the commanded label with the planner's cost. */
	struct InstanceCost
	{
		int id = 0;
		double euclidean = 0;
		/** Nothing when there is no path. */
		std::optional<double> cost;
	};

	/** Loads the scene and the map; throws IoError/ConfigError naming the
	 * file. */
	explicit NavigationRun(const Settings& settings);
	~NavigationRun();

	/** Drives `command` from the true pose `start`; writes the outputs. */
	SimulatedNavigation::Result run(
	    const NavCommand& command, const mrpt::math::TPose2D& start);

	/** Every map instance of a nearest-label command's label with its
	 * planner cost from `start` (the reached one should be the cheapest);
	 * empty for other commands. */
	std::vector<InstanceCost> instanceCosts(
	    const NavCommand& command, const mrpt::math::TPose2D& start) const;

	const SemanticMap& map() const { return m_map; }
	/** The labels taken from the scene (instancesFromScene). */
	const std::vector<std::string>& addedFromScene() const { return m_added; }
	/** Paths written by run() ("" without outDir). */
	const std::string& navlogPath() const { return m_navlog; }
	const std::string& pngPath() const { return m_png; }

private:
	Settings m_settings;
	Scene m_scene;
	SemanticMap m_map;
	std::vector<std::string> m_added;
	std::string m_navlog, m_png;
};

}  // namespace semnav
