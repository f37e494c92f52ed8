/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CConfigFile.h>
#include <mrpt/config/CLoadableOptions.h>
#include <semnav/detection/CascadeDetector.h>
#include <semnav/localization/MappingLocalizer.h>
#include <semnav/nav/NavigationConfig.h>
#include <semnav/perception/PerceptionPipeline.h>
#include <semnav/runtime/RobotSession.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace semnav
{
/** Everything semnav-robot is configured with, named by one INI file
 * (config/robot.ini): [RobotSetup] (this struct's files and choices),
 * [SemnavRobot] (RobotSession), [LiveSweepSource], the laser + tilt head
 * section (laser_section, the keys of the rawlog-grabber plugin's
 * CTiltingLMS2xx section), and the base driver's section ([Ros1Base], or
 * the plugin's). The perception, cascade, localization, planning and
 * navigation files it names are loaded too; relative paths are relative to
 * the robot INI's directory, empty ones are the shipped config/ files. */
struct RobotSetup
{
	struct TOptions : public mrpt::config::CLoadableOptions
	{
		void loadFromConfigFile(
		    const mrpt::config::CConfigFileBase& c,
		    const std::string& section) override;
		void saveToConfigFile(
		    mrpt::config::CConfigFileBase& c,
		    const std::string& section) const override;

		/** base: the robot base driver: ros1 or plugin (--plugin). */
		std::string base = "ros1";
		/** base_section: the driver's INI section. */
		std::string baseSection = "Ros1Base";
		/** laser_section: the tilting LMS2xx's section. */
		std::string laserSection = "TILT_LMS";
		/** map_dir: the starting map (semnav-map); empty: an empty map. */
		std::string mapDir;
		/** out_dir: robot.rawlog, the map, pictures and the navlog. */
		std::string outDir = "semnav-robot-out";
		/** The other configuration files (empty: shipped); cascade_config
		 * = none: rules only, no object detection. */
		std::string navigationConfig, planningConfig, localizationConfig,
		    perceptionConfig, cascadeConfig, mapConfig;
		/** control_period_s: the navigator's step. */
		double controlPeriod = 0.1;
	};

	TOptions files;
	RobotSession::TOptions session;
	NavigationConfig navigation;
	MappingLocalizer::TOptions localization;
	PerceptionPipeline::TOptions perception;
	std::optional<CascadeDetector::TOptions> cascades;
	/** The robot INI itself, for the laser's and the base's sections. */
	std::shared_ptr<mrpt::config::CConfigFile> ini;
	std::string iniPath;

	/** Loads `path` and the files it names; throws ConfigError naming the
	 * file, section and key (unknown sections and keys are errors; the
	 * plugin's section is checked by the plugin). With a base plugin
	 * (`pluginSection`, its name) base = plugin and the base's section is
	 * the plugin's. */
	static RobotSetup load(
	    const std::string& path, const std::string& pluginSection = "");
	/** `p` relative to the robot INI's directory ("" stays ""). */
	std::string resolve(const std::string& p) const;
};

}  // namespace semnav
