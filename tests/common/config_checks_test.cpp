/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <semnav/common/ConfigChecks.h>
#include <semnav/common/Error.h>

#include <filesystem>
#include <fstream>

using namespace semnav;

namespace
{
std::string messageOf(const std::function<void()>& f)
{
	try
	{
		f();
	}
	catch (const ConfigError& e)
	{
		return e.what();
	}
	return "";
}
}  // namespace

TEST(ConfigChecks, ReadsValuesAndKeepsDefaults)
{
	mrpt::config::CConfigFileMemory c("[A]\nx_m = 2.5\nn = 7\nflag = yes\n");
	EXPECT_DOUBLE_EQ(readChecked(c, "A", "x_m", 1.0, 0, 10), 2.5);
	EXPECT_DOUBLE_EQ(readChecked(c, "A", "absent", 1.0, 0, 10), 1.0);
	EXPECT_EQ(readCheckedInt(c, "A", "n", 3, 0, 10), 7);
	EXPECT_TRUE(readCheckedBool(c, "A", "flag", false));
	EXPECT_NO_THROW(checkKnownKeys(c, "A", {"x_m", "n", "flag"}));
}

TEST(ConfigChecks, ErrorsNameSectionAndKey)
{
	mrpt::config::CConfigFileMemory c(
	    "[A]\nx_m = 12\ny_m = abc\nn = 2.5\nflag = maybe\ntypo = 1\n");
	EXPECT_NE(
	    messageOf([&] { readChecked(c, "A", "x_m", 1, 0, 10); })
	        .find("[A] x_m"),
	    std::string::npos);
	EXPECT_NE(
	    messageOf([&] { readChecked(c, "A", "y_m", 1, 0, 10); })
	        .find("not a number"),
	    std::string::npos);
	EXPECT_NE(
	    messageOf([&] { readCheckedInt(c, "A", "n", 1, 0, 10); })
	        .find("integer"),
	    std::string::npos);
	EXPECT_NE(
	    messageOf([&] { readCheckedBool(c, "A", "flag", true); }).find("flag"),
	    std::string::npos);
	const auto m = messageOf(
	    [&] {
		    checkKnownKeys(c, "A", {"x_m", "y_m", "n", "flag"});
	    });
	EXPECT_NE(m.find("unknown key [A] typo"), std::string::npos) << m;
}

TEST(ConfigChecks, OpenIniFileRejectsUnknownSectionsAndMissingFiles)
{
	const auto p = std::filesystem::temp_directory_path() /
	               ("semnav_cfg_" + std::to_string(::getpid()) + ".ini");
	std::ofstream(p) << "[Known]\na = 1\n[Stray]\nb = 2\n";
	const auto m = messageOf([&] { openIniFile(p.string(), {"Known"}); });
	EXPECT_NE(m.find("[Stray]"), std::string::npos) << m;
	EXPECT_NO_THROW(openIniFile(p.string(), {"Known", "Stray"}));
	EXPECT_NE(
	    messageOf([&] { openIniFile("/nonexistent.ini", {}); })
	        .find("not found"),
	    std::string::npos);
	std::filesystem::remove(p);
}

// Found by fuzz_ini (fuzz/): MRPT's INI parser throws its own multi-line
// exception on an unclosed ${...}; openIniFile says it in one line.
TEST(ConfigChecks, OpenIniFileNamesMrptParseErrors)
{
	const auto p = std::filesystem::temp_directory_path() /
	               ("semnav_cfg_env_" + std::to_string(::getpid()) + ".ini");
	std::ofstream(p) << "[Known]\nx = $env{ts.json\n";
	const auto m = messageOf([&] { openIniFile(p.string(), {"Known"}); });
	EXPECT_EQ(
	    m, p.string() + ": Line 2: Expected closing `}` near: `$env{ts.json`")
	    << m;
	std::filesystem::remove(p);
}
