/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <semnav/common/Error.h>
#include <semnav/runtime/RobotSetup.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

using semnav::RobotSetup;

namespace
{
const std::string kConfig = std::string(SEMNAV_SOURCE_DIR) + "/config/";

/** robot-emulated.ini with `edit` applied (sed-like: appended lines or a
 * replaced line), written next to the shipped files' copy. */
std::string variant(
    const std::string& name, const std::string& from, const std::string& to)
{
	std::ifstream in(kConfig + "robot-emulated.ini");
	std::stringstream ss;
	ss << in.rdbuf();
	std::string text = ss.str();
	if (!from.empty())
	{
		const auto at = text.find(from);
		EXPECT_NE(at, std::string::npos) << from;
		text.replace(at, from.size(), to);
	}
	else
		text += to;
	const auto dir = std::filesystem::temp_directory_path() /
	                 ("semnav-setup-" + std::to_string(::getpid()));
	std::filesystem::create_directories(dir);
	const std::string path = (dir / name).string();
	std::ofstream(path) << text;
	return path;
}

std::string loadError(const std::string& path, const std::string& plugin = "")
{
	try
	{
		RobotSetup::load(path, plugin);
	}
	catch (const semnav::ConfigError& e)
	{
		return e.what();
	}
	return "";
}
}  // namespace

TEST(RobotSetup, TheShippedFilesLoad)
{
	for (const char* f : {"robot.ini", "robot-emulated.ini"})
	{
		const RobotSetup s = RobotSetup::load(kConfig + f);
		EXPECT_EQ(s.files.base, "ros1") << f;
		EXPECT_TRUE(s.ini->sectionExists("TILT_LMS")) << f;
		EXPECT_TRUE(s.cascades.has_value()) << f;
		EXPECT_EQ(
		    s.session.localize, semnav::StopAndScanLocalizer::Mode::Global);
		EXPECT_TRUE(s.session.growMap);
	}
	EXPECT_EQ(
	    RobotSetup::load(kConfig + "robot.ini")
	        .ini->read_string("TILT_LMS", "COM_port_LIN", ""),
	    "/dev/ttyUSB0");
}

TEST(RobotSetup, BadFilesAreOneLineErrorsNamingFileSectionAndKey)
{
	EXPECT_NE(
	    loadError(variant("a.ini", "", "\n[Extra]\nx = 1\n")).find("[Extra]"),
	    std::string::npos);
	const std::string key = loadError(
	    variant("b.ini", "grow_map = true", "grow_map = true\ngrow_maps = 1"));
	EXPECT_NE(key.find("grow_maps"), std::string::npos) << key;
	EXPECT_NE(key.find("b.ini"), std::string::npos) << key;
	EXPECT_NE(
	    loadError(
	        variant("c.ini", "laser_silence_s = 0.2", "laser_silence_s = 0"))
	        .find("laser_silence_s"),
	    std::string::npos);
	EXPECT_NE(
	    loadError(variant("d.ini", "localize = global", "localize = tracking"))
	        .find("start_pose"),
	    std::string::npos);
	EXPECT_NE(
	    loadError(variant("e.ini", "base = ros1", "base = plugin"))
	        .find("--plugin"),
	    std::string::npos);
	EXPECT_NE(
	    loadError(variant("f.ini", "base = ros1", "base = can")).find("can"),
	    std::string::npos);
	EXPECT_NE(
	    loadError("/nonexistent/robot.ini").find("no such file"),
	    std::string::npos);
	for (const auto& e : {loadError(variant("g.ini", "", "\n[Extra]\n"))})
		EXPECT_EQ(e.find('\n'), std::string::npos) << e;
}

TEST(RobotSetup, APluginNamesTheBaseSection)
{
	const std::string path =
	    variant("h.ini", "", "\n[ExampleBase]\nwatchdog_s = 0.5\n");
	EXPECT_NE(loadError(path).find("[ExampleBase]"), std::string::npos);
	const RobotSetup s = RobotSetup::load(path, "ExampleBase");
	EXPECT_EQ(s.files.base, "plugin");
	EXPECT_EQ(s.files.baseSection, "ExampleBase");
}

TEST(RobotSetup, RelativePathsAreRelativeToTheRobotIni)
{
	const RobotSetup s = RobotSetup::load(kConfig + "robot.ini");
	EXPECT_EQ(
	    std::filesystem::path(s.resolve("maps/office")).lexically_normal(),
	    std::filesystem::path(kConfig + "maps/office").lexically_normal());
	EXPECT_EQ(s.resolve("/abs/map"), "/abs/map");
	EXPECT_EQ(s.resolve(""), "");
}
