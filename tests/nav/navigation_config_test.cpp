/* semnav: semantic navigation from tilting-laser sweeps */
// config/navigation.ini (with config/planning.ini) loads, matches the
// planner's robot, and bad sections, keys and values are errors.
#include <gtest/gtest.h>
#include <semnav/common/Error.h>
#include <semnav/nav/NavigationConfig.h>

#include <filesystem>
#include <fstream>
#include <sstream>

using namespace semnav;
namespace fs = std::filesystem;

namespace
{
const std::string kNav =
    std::string(SEMNAV_SOURCE_DIR) + "/config/navigation.ini";
const std::string kPlan =
    std::string(SEMNAV_SOURCE_DIR) + "/config/planning.ini";

std::string shipped()
{
	std::ifstream f(kNav);
	std::stringstream ss;
	ss << f.rdbuf();
	return ss.str();
}

/** The shipped file with `from` replaced by `to`, written to a temp file. */
std::string variant(const std::string& from, const std::string& to)
{
	std::string s = shipped();
	const auto at = s.find(from);
	EXPECT_NE(at, std::string::npos) << from;
	s.replace(at, from.size(), to);
	const fs::path p = fs::temp_directory_path() /
	                   ("semnav_navcfg_" + std::to_string(::getpid()) + ".ini");
	std::ofstream(p) << s;
	return p.string();
}

std::string errorOf(const std::string& path)
{
	try
	{
		NavigationConfig::load(path, kPlan);
	}
	catch (const ConfigError& e)
	{
		return e.what();
	}
	return "";
}
}  // namespace

TEST(NavigationConfig, ShippedFilesLoad)
{
	const auto c = NavigationConfig::load(kNav, kPlan);
	EXPECT_EQ(c.navigator.profile, "safe");
	EXPECT_DOUBLE_EQ(c.navigator.goalAllowedDistance, 0.15);
	EXPECT_DOUBLE_EQ(c.sweepObstacles.maxHeight, 1.0);
	EXPECT_DOUBLE_EQ(c.robotInterface.alignMaxSpeedDeg, 45);
	// The PTG shape and the planner's C-space agree.
	EXPECT_NEAR(
	    c.mrptSections->read_double(
	        "CReactiveNavigationSystem", "RobotModel_circular_shape_radius", 0),
	    c.traversability.robotRadius, 0.02);
	EXPECT_EQ(
	    c.mrptSections->read_int("CReactiveNavigationSystem", "PTG_COUNT", 0),
	    3);
	// MRPT macros are expanded.
	EXPECT_DOUBLE_EQ(
	    c.mrptSections->read_double(
	        "CAbstractPTGBasedReactive", "robotMax_V_mps", 0),
	    0.4);
}

TEST(NavigationConfig, BadInputIsAnError)
{
	EXPECT_NE(
	    errorOf(variant("max_stalled_replans = 25", "max_stalled_replanz = 25"))
	        .find("max_stalled_replanz"),
	    std::string::npos);
	EXPECT_NE(
	    errorOf(variant("max_stalled_replans = 25", "max_stalled_replans = -3"))
	        .find("max_stalled_replans"),
	    std::string::npos);
	EXPECT_NE(errorOf(variant("profile = safe", "profile = fastest")), "");
	EXPECT_NE(
	    errorOf(variant("max_age_s = 60", "max_age_s = old")).find("max_age_s"),
	    std::string::npos);
	EXPECT_NE(
	    errorOf(variant("align_gain = 2.25", "align_gain = 0"))
	        .find("align_gain"),
	    std::string::npos);
	// A typo in one of MRPT's keys (MRPT itself would ignore it).
	const std::string e =
	    errorOf(variant("secure_distance_start", "secure_distance_strat"));
	EXPECT_NE(e.find("secure_distance_strat"), std::string::npos) << e;
	EXPECT_NE(
	    errorOf(variant("[SweepObstacles]", "[SweepObstacle]"))
	        .find("SweepObstacle"),
	    std::string::npos);
	EXPECT_NE(errorOf("/nonexistent/navigation.ini"), "");
	EXPECT_EQ(errorOf(kNav), "");
}

TEST(NavigationConfig, EmptyFileNamesTheFileAndTheMissingKey)
{
	const fs::path p =
	    fs::temp_directory_path() /
	    ("semnav_navcfg_empty_" + std::to_string(::getpid()) + ".ini");
	std::ofstream(p).close();
	const std::string e = errorOf(p.string());
	fs::remove(p);
	EXPECT_EQ(e.find('\n'), std::string::npos) << "one line: " << e;
	EXPECT_EQ(e.rfind(p.string() + ": [", 0), 0u) << e;
	EXPECT_NE(e.find(" is missing"), std::string::npos) << e;
	EXPECT_EQ(e.find("===="), std::string::npos) << e;
}
