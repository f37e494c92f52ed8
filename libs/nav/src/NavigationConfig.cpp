/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/config/CConfigFile.h>
#include <mrpt/kinematics/CVehicleSimul_DiffDriven.h>
#include <mrpt/nav/reactive/CReactiveNavigationSystem.h>
#include <mrpt/nav/reactive/CRobot2NavInterfaceForSimulator.h>
#include <semnav/common/ConfigChecks.h>
#include <semnav/common/Error.h>
#include <semnav/nav/NavigationConfig.h>
#include <semnav/planning/SemanticPlanner.h>

#include <algorithm>
#include <cctype>
#include <regex>
#include <set>

namespace semnav
{
namespace
{
std::string lower(std::string s)
{
	while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back())))
		s.pop_back();
	std::transform(
	    s.begin(), s.end(), s.begin(),
	    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
	return s;
}

/** PTG and robot-shape keys of [CReactiveNavigationSystem], which MRPT
 * reads per PTG but does not write back. */
bool dynamicKey(const std::string& section, const std::string& key)
{
	if (section != "CReactiveNavigationSystem") return false;
	if (key.rfind("RobotModel_", 0) == 0) return true;
	if (key.size() > 4 && key.rfind("PTG", 0) == 0 &&
	    std::isdigit(static_cast<unsigned char>(key[3])))
		return true;
	return false;
}

/** What MRPT's exception `what` says, in one line: its "Message:" line,
 * and a missing required key as "[section] key is missing". */
std::string mrptComplaint(const std::string& what)
{
	std::string msg = what;
	if (const auto m = what.find("Message:"); m != std::string::npos)
	{
		const auto b = what.find_first_not_of(' ', m + 8);
		msg = what.substr(b, what.find('\n', b) - b);
	}
	else
		msg = msg.substr(0, msg.find('\n'));
	static const std::regex missing(
	    "Value for '([^']*)' not found in config file in section '([^']*)'");
	std::smatch k;
	if (std::regex_search(msg, k, missing))
		return "[" + k[2].str() + "] " + k[1].str() +
		       " is missing (MRPT's navigator requires it; the shipped "
		       "config/navigation.ini has every key)";
	return "MRPT rejects the navigation sections: " + msg.substr(0, 300);
}

/** Keys MRPT writes back for the sections of `cfg`: every key it reads.
 * (Filled in place: CConfigFileMemory must not be copied.) */
void mrptEcho(
    const mrpt::config::CConfigFileBase& cfg,
    mrpt::config::CConfigFileMemory& out)
{
	struct NullRobot
	    : public mrpt::nav::CRobot2NavInterfaceForSimulator_DiffDriven
	{
		explicit NullRobot(mrpt::kinematics::CVehicleSimul_DiffDriven& s)
		    : mrpt::nav::CRobot2NavInterfaceForSimulator_DiffDriven(s)
		{
		}
		bool senseObstacles(
		    mrpt::maps::CSimplePointsMap&, mrpt::system::TTimeStamp&) override
		{
			return false;
		}
	};
	mrpt::kinematics::CVehicleSimul_DiffDriven sim;
	NullRobot robot(sim);
	struct Quiet : public mrpt::nav::CReactiveNavigationSystem
	{
		explicit Quiet(mrpt::nav::CRobot2NavInterface& r)
		    : mrpt::nav::CReactiveNavigationSystem(r, false, false)
		{
			m_timlog_delays.enable(false);
		}
	} nav(robot);
	nav.setMinLoggingLevel(mrpt::system::LVL_ERROR);
	nav.loadConfigFile(cfg);
	nav.saveConfigFile(out);
}
}  // namespace

const std::vector<std::string>& NavigationConfig::mrptSectionNames()
{
	static const std::vector<std::string> names{
	    "CAbstractNavigator",
	    "CWaypointsNavigator",
	    "CAbstractPTGBasedReactive",
	    "CPointCloudFilterByDistance",
	    "CHolonomicFullEval",
	    "CHolonomicND",
	    "CHolonomicVFF",
	    "CMultiObjectiveMotionOptimizerBase",
	    "CMultiObjMotionOpt_Scalarization",
	    "CReactiveNavigationSystem"};
	return names;
}

NavigationConfig NavigationConfig::load(
    const std::string& navigationIni, const std::string& planningIni,
    const std::vector<ExtraSection>& extra)
{
	NavigationConfig c;
	std::vector<ExtraSection> semnavSections{
	    {"SemanticNavigator", &c.navigator},
	    {"StopAndScan", &c.stopAndScan},
	    {"ViewPlanner", &c.viewPlanner},
	    {"RobotNavInterface", &c.robotInterface},
	    {"SweepObstacles", &c.sweepObstacles}};
	semnavSections.insert(semnavSections.end(), extra.begin(), extra.end());
	std::set<std::string> ours;
	std::vector<std::string> known;
	for (const auto& s : semnavSections)
	{
		ours.insert(s.name);
		known.push_back(s.name);
	}
	for (const auto& s : mrptSectionNames()) known.push_back(s);
	const auto ini = openIniFile(navigationIni, known);
	try
	{
		for (const auto& s : semnavSections)
			s.options->loadFromConfigFile(*ini, s.name);
	}
	catch (const ConfigError& e)
	{
		throw ConfigError(navigationIni + ": " + e.what());
	}
	auto mrptSections = std::make_shared<mrpt::config::CConfigFileMemory>();
	std::vector<std::string> sections;
	ini->getAllSections(sections);
	for (const auto& s : sections)
	{
		if (ours.count(s)) continue;
		std::vector<std::string> keys;
		ini->getAllKeys(s, keys);
		for (const auto& k : keys)
			mrptSections->write(s, k, ini->read_string(s, k, ""));
	}
	// Unknown keys of MRPT's sections: MRPT echoes every key it reads.
	try
	{
		mrpt::config::CConfigFileMemory echo;
		mrptEcho(*mrptSections, echo);
		for (const auto& s : sections)
		{
			if (ours.count(s)) continue;
			std::vector<std::string> keys, echoed;
			ini->getAllKeys(s, keys);
			echo.getAllKeys(s, echoed);
			std::set<std::string> ok;
			for (const auto& k : echoed) ok.insert(lower(k));
			for (const auto& k : keys)
				if (!ok.count(lower(k)) && !dynamicKey(s, k))
					throw ConfigError(
					    navigationIni + ": [" + s + "] unknown key '" + k +
					    "' (MRPT does not read it)");
		}
	}
	catch (const ConfigError&)
	{
		throw;
	}
	catch (const std::exception& e)
	{
		throw ConfigError(navigationIni + ": " + mrptComplaint(e.what()));
	}
	c.mrptSections = std::move(mrptSections);
	if (!planningIni.empty())
	{
		const auto p = openIniFile(
		    planningIni,
		    {"CnnPlanner", "Traversability", "SemanticMap", "TravelCost"});
		try
		{
			c.cnn.loadFromConfigFile(*p, "CnnPlanner");
			c.traversability.loadFromConfigFile(*p, "Traversability");
			c.map.loadFromConfigFile(*p, "SemanticMap");
			c.map.cost.loadFromConfigFile(*p, "TravelCost");
		}
		catch (const ConfigError& e)
		{
			throw ConfigError(planningIni + ": " + e.what());
		}
	}
	return c;
}

CostProfile NavigationConfig::navigationProfile() const
{
	return navigator.profile == "planning"
	           ? traversability.profile
	           : costProfileFromName(navigator.profile);
}

TraversabilityGrid NavigationConfig::navigationTraversability(
    const SemanticMap& m) const
{
	return SemanticPlanner(m, cnn, traversability)
	    .traversability(navigationProfile());
}

}  // namespace semnav
