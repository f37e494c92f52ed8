/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/ConfigChecks.h>
#include <semnav/common/Error.h>
#include <semnav/common/IniSections.h>
#include <semnav/common/OptionTable.h>
#include <semnav/common/ShippedConfig.h>
#include <semnav/hwdrivers/LiveSweepSource.h>
#include <semnav/runtime/RobotSetup.h>
#include <semnav/scan/SweepAssembler.h>

#include <filesystem>

namespace semnav
{
namespace
{
using O = RobotSetup::TOptions;
const OptionTable<O>& optionTable()
{
	static const auto t =
	    OptionTable<O>()
	        .text(
	            "base", &O::base,
	            "The robot base driver: ros1, or plugin (semnav-robot "
	            "--plugin libX.so).")
	        .text("base_section", &O::baseSection, "The driver's section.")
	        .text(
	            "laser_section", &O::laserSection,
	            "The tilting LMS2xx + head section (the rawlog-grabber "
	            "plugin's keys).")
	        .text(
	            "map_dir", &O::mapDir,
	            "The starting map (a semnav-map directory); empty: start "
	            "with an empty map.")
	        .text(
	            "out_dir", &O::outDir,
	            "robot.rawlog, the map, pictures and the navigation log.")
	        .text(
	            "navigation_config", &O::navigationConfig,
	            "Navigation INI (empty: the shipped navigation.ini).")
	        .text(
	            "planning_config", &O::planningConfig,
	            "Planning INI (empty: the shipped planning.ini).")
	        .text(
	            "localization_config", &O::localizationConfig,
	            "Localization INI (empty: the shipped localization.ini).")
	        .text(
	            "perception_config", &O::perceptionConfig,
	            "Perception INI (empty: the shipped perception.ini).")
	        .text(
	            "cascade_config", &O::cascadeConfig,
	            "Object detection INI (empty: the shipped cascade.ini; none: "
	            "rules only).")
	        .text(
	            "map_config", &O::mapConfig,
	            "[SemanticMap] and [TravelCost] of a new map (empty: the "
	            "shipped map.ini).")
	        .real(
	            "control_period_s", &O::controlPeriod, 0.02, 1,
	            "The navigator's control period.")
	        .check(
	            [](const O& o)
	            { return o.base == "ros1" || o.base == "plugin"; },
	            [](const O& o) {
		            return "base = '" + o.base +
		                   "' is not one of ros1 | plugin";
	            });
	return t;
}
}  // namespace

SEMNAV_OPTIONS_FROM_TABLE(RobotSetup::TOptions, optionTable())

std::string RobotSetup::resolve(const std::string& p) const
{
	if (p.empty() || std::filesystem::path(p).is_absolute()) return p;
	return (std::filesystem::path(iniPath).parent_path() / p).string();
}

RobotSetup RobotSetup::load(
    const std::string& path, const std::string& pluginSection)
{
	RobotSetup s;
	s.iniPath = path;
	if (!std::filesystem::exists(path))
		throw ConfigError(path + ": no such file");
	s.ini = std::make_shared<mrpt::config::CConfigFile>(path);
	try
	{
		s.files.loadFromConfigFile(*s.ini, "RobotSetup");
		s.session.loadFromConfigFile(*s.ini, "SemnavRobot");
		LiveSweepSource::TOptions live;
		live.loadFromConfigFile(*s.ini, "LiveSweepSource");
	}
	catch (const ConfigError& e)
	{
		throw ConfigError(path + ": " + e.what());
	}
	if (!pluginSection.empty())
	{
		s.files.base = "plugin";
		s.files.baseSection = pluginSection;
	}
	else if (s.files.base == "plugin")
		throw ConfigError(path + ": base = plugin needs --plugin libX.so");
	std::vector<std::string> sections;
	s.ini->getAllSections(sections);
	for (const auto& sec : sections)
		if (sec != "RobotSetup" && sec != "SemnavRobot" &&
		    sec != "LiveSweepSource" && sec != "Ros1Base" &&
		    sec != "Ros1Operator" && sec != s.files.laserSection &&
		    sec != s.files.baseSection)
			throw ConfigError(
			    path + ": unknown section [" + sec +
			    "] (expected RobotSetup, SemnavRobot, LiveSweepSource, "
			    "Ros1Base, Ros1Operator, " +
			    s.files.laserSection + ", " + s.files.baseSection + ")");
	if (!s.ini->sectionExists(s.files.laserSection))
		throw ConfigError(
		    path + ": no laser section [" + s.files.laserSection + "]");
	const auto file = [&](const std::string& p, const std::string& shipped)
	{ return p.empty() ? ShippedConfig::path(shipped) : s.resolve(p); };
	s.navigation = NavigationConfig::load(
	    file(s.files.navigationConfig, "navigation.ini"),
	    file(s.files.planningConfig, "planning.ini"));
	IniSections localization, perception, map;
	localization.add(
	    s.localization, "", MappingLocalizer::TOptions::sections());
	localization.load(file(s.files.localizationConfig, "localization.ini"));
	perception.add(s.perception, "", PerceptionPipeline::sections());
	perception.load(file(s.files.perceptionConfig, "perception.ini"));
	SweepAssembler::TOptions assembler;
	map.add(s.navigation.map, "SemanticMap")
	    .add(s.navigation.map.cost, "TravelCost")
	    .add(assembler, "SweepAssembler");
	map.load(file(s.files.mapConfig, "map.ini"));
	if (s.files.cascadeConfig != "none")
		s.cascades = CascadeDetector::TOptions::fromIniFile(
		    file(s.files.cascadeConfig, "cascade.ini"));
	return s;
}

}  // namespace semnav
