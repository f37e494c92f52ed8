/* semnav: semantic navigation from tilting-laser sweeps */
// The semnav-sim command line: exit codes, one-line errors, --json.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "../TestPaths.h"
#include "AppRunner.h"

namespace fs = std::filesystem;
using semnav::test::AppRun;
using semnav::test::lineCount;
using semnav::test::runApp;

namespace
{
AppRun runSim(const std::string& args)
{
	return runApp("semnav-sim", args);
}

}  // namespace

TEST(SemnavSimCli, JsonSummaryOnSuccess)
{
	const fs::path out = fs::temp_directory_path() /
	                     ("semnav_cli_out_" + std::to_string(::getpid()));
	const AppRun r = runSim(
	    "--scene " + semnav::test::kSourceDir +
	    "/datasets/outdoor/outdoor.yaml --out " + out.string() +
	    " --seed 3 --json");
	ASSERT_EQ(r.code, 0) << r.err;
	const auto j = nlohmann::json::parse(r.out);
	EXPECT_EQ(j.at("sweeps").get<int>(), 7);
	EXPECT_EQ(j.at("scans").get<int>(), 7 * 211);
	EXPECT_TRUE(fs::exists(j.at("rawlog").get<std::string>()));
	EXPECT_TRUE(fs::exists(j.at("gt").get<std::string>()));
	EXPECT_TRUE(r.err.empty()) << "no progress bar off a TTY: " << r.err;
	fs::remove_all(out);
}

TEST(SemnavSimCli, BadUsageIsOneLineAndExitTwo)
{
	for (const std::string args :
	     {"--bogus", "--scene x.yaml", "--scene x.yaml --out /tmp/x --seed -4"})
	{
		const AppRun r = runSim(args);
		EXPECT_EQ(r.code, 2) << args;
		EXPECT_EQ(lineCount(r.err), 1u) << args << ": " << r.err;
		EXPECT_EQ(r.err.rfind("semnav-sim: ", 0), 0u) << r.err;
	}
}

TEST(SemnavSimCli, BadSceneIsOneLineNamingFileLineAndKey)
{
	const fs::path bad =
	    fs::temp_directory_path() /
	    ("semnav_cli_bad_" + std::to_string(::getpid()) + ".yaml");
	{
		std::FILE* f = std::fopen(bad.c_str(), "w");
		std::fputs(
		    "name: x\nbounds: [0, 0, 4, 4]\ntrajectory: [[1, 1, "
		    "0]]\nobjects:\n  - {label: wall, box: {center: [1, 1, 1], size: "
		    "[1, -1, 1]}}\n",
		    f);
		std::fclose(f);
	}
	const AppRun r =
	    runSim("--scene " + bad.string() + " --out /tmp/semnav_never");
	EXPECT_EQ(r.code, 1);
	EXPECT_EQ(lineCount(r.err), 1u) << r.err;
	EXPECT_NE(r.err.find(bad.string() + ":5:"), std::string::npos) << r.err;
	EXPECT_NE(r.err.find("objects[0].box.size"), std::string::npos) << r.err;
	EXPECT_FALSE(fs::exists("/tmp/semnav_never/x.rawlog"));
	fs::remove(bad);
	const AppRun m =
	    runSim("--scene /nonexistent.yaml --out /tmp/semnav_never");
	EXPECT_EQ(m.code, 1);
	EXPECT_NE(m.err.find("/nonexistent.yaml"), std::string::npos) << m.err;
}

namespace
{
/** Runs semnav-sim on the scene `yaml` (written to a file named after
 * `name`): exit 1 and one line "<file>:<where>". */
void expectSceneError(
    const std::string& name, const std::string& yaml, const std::string& where)
{
	const fs::path scene =
	    fs::temp_directory_path() /
	    ("semnav_cli_" + name + "_" + std::to_string(::getpid()) + ".yaml");
	std::ofstream(scene) << yaml;
	const AppRun r =
	    runSim("--scene " + scene.string() + " --out /tmp/semnav_never");
	fs::remove(scene);
	EXPECT_EQ(r.code, 1);
	EXPECT_EQ(lineCount(r.err), 1u) << r.err;
	EXPECT_NE(r.err.find(scene.string() + ":" + where), std::string::npos)
	    << r.err;
}
}  // namespace

TEST(SemnavSimCli, AbsurdSizeIsOneLineNamingKeyAndLimit)
{
	expectSceneError(
	    "huge",
	    "name: x\nbounds: [0, 0, 4, 4]\nobjects:\n  - {label: wall, box: "
	    "{center: [3, 3, 1], size: [1e30, 1, 2]}}\ntrajectory: [[1, 1, 0]]\n",
	    "4: objects[0].box.size[0]: must be at most 1000 m, got 1e+30");
}

TEST(SemnavSimCli, PoseInsideAWallIsOneLineNamingIndexAndLine)
{
	expectSceneError(
	    "inwall",
	    "name: x\nbounds: [0, 0, 4, 4]\nobjects:\n  - {label: wall, box: "
	    "{center: [2, 2, 1], size: [1, 1, 2]}}\ntrajectory:\n  - [1, 1, 0]\n"
	    "  - [2, 2, 0]\n",
	    "7: trajectory[1]: pose (2, 2) is inside objects[0] (wall, line 4)");
}
