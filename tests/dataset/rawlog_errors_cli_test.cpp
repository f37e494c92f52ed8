/* semnav: semantic navigation from tilting-laser sweeps */
// Rawlogs without sweeps or cut short, through the apps (issue 39): an
// empty or odometry-only rawlog is "no sweeps in R" and exit 1 (no 0 x 0
// map); semnav-device-emulator --check on a truncated capture says where
// it ends and exits 1 (0 with --truncated-ok). Random corruptions:
// scripts/corrupt-rawlogs (ctest corrupt_rawlogs).
#include <gtest/gtest.h>
#include <semnav/scan/RawlogWriter.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "../scan/ScanTestUtils.h"
#include "AppRunner.h"

using namespace semnav::test;
namespace fs = std::filesystem;

namespace
{
const fs::path kRawlogErrorsTmp =
    fs::temp_directory_path() /
    ("semnav_rawlog_errors_" + std::to_string(::getpid()));

/** An empty rawlog and one of three odometry readings. */
std::vector<std::string> sweeplessRawlogs()
{
	fs::create_directories(kRawlogErrorsTmp);
	const std::string empty = (kRawlogErrorsTmp / "empty.rawlog").string();
	semnav::RawlogWriter(empty).commit();
	const std::string odo = (kRawlogErrorsTmp / "odometry.rawlog").string();
	semnav::RawlogWriter w(odo);
	for (int i = 0; i < 3; i++) w.write(*makeOdometry(i, 0, 0));
	w.commit();
	return {empty, odo};
}
}  // namespace

TEST(RawlogErrorsCli, NoSweepsIsOneLineAndExit1)
{
	for (const std::string& rawlog : sweeplessRawlogs())
		for (const std::string app : {"semnav-map", "semnav-perceive"})
		{
			const fs::path out = kRawlogErrorsTmp / (app + "_out");
			fs::remove_all(out);
			const AppRun r = runApp(
			    app,
			    "--no-cascades --rawlog " + rawlog + " --out " + out.string());
			EXPECT_EQ(r.code, 1) << app << " " << rawlog << r.err;
			EXPECT_EQ(lineCount(r.err), 1u) << r.err;
			EXPECT_NE(r.err.find("no sweeps in " + rawlog), std::string::npos)
			    << r.err;
			if (app == "semnav-map")
				EXPECT_FALSE(fs::exists(out / "map.yaml")) << "a 0 x 0 map";
		}
	fs::remove_all(kRawlogErrorsTmp);
}

TEST(RawlogErrorsCli, CheckOfATruncatedCaptureIsNotSilent)
{
	// One stop of the office, simulated; then its last third cut off.
	const std::string source = SEMNAV_SOURCE_DIR;
	fs::create_directories(kRawlogErrorsTmp);
	const fs::path scene = kRawlogErrorsTmp / "office.yaml";
	{
		std::ifstream in(source + "/datasets/office/office.yaml");
		std::ofstream out(scene);
		std::string line;
		bool trajectory = false;
		int kept = 0;
		while (std::getline(in, line))
		{
			if (line.rfind("trajectory:", 0) == 0)
				trajectory = true;
			else if (trajectory && line.rfind("  - [", 0) == 0 && kept++)
				continue;
			out << line << "\n";
		}
	}
	const AppRun sim = runApp(
	    "semnav-sim", "--scene " + scene.string() + " --out " +
	                      (kRawlogErrorsTmp / "sim").string());
	ASSERT_EQ(sim.code, 0) << sim.err;
	const fs::path rawlog = kRawlogErrorsTmp / "sim" / "office.rawlog";
	fs::resize_file(rawlog, fs::file_size(rawlog) * 2 / 3);

	const std::string args =
	    "--scene " + scene.string() + " --json --check " + rawlog.string();
	const AppRun r = runApp("semnav-device-emulator", args);
	EXPECT_EQ(r.code, 1) << r.err;
	EXPECT_EQ(lineCount(r.err), 1u) << r.err;
	EXPECT_NE(
	    r.err.find(rawlog.string() + " is truncated at object"),
	    std::string::npos)
	    << r.err;
	const auto j = nlohmann::json::parse(r.out);  // the partial check
	EXPECT_TRUE(j.at("truncated").get<bool>());
	EXPECT_GT(j.at("lines").get<int>(), 50);

	const AppRun ok =
	    runApp("semnav-device-emulator", args + " --truncated-ok");
	EXPECT_EQ(ok.code, 0) << ok.err;
	EXPECT_EQ(nlohmann::json::parse(ok.out).at("lines"), j.at("lines"));
	fs::remove_all(kRawlogErrorsTmp);
}

TEST(RawlogErrorsCli, ADirectoryAsRawlogIsNamed)
{
	const fs::path dir = kRawlogErrorsTmp / "a_directory.rawlog";
	fs::create_directories(dir);
	for (const std::string app : {"semnav-map", "semnav-perceive"})
	{
		const AppRun r = runApp(
		    app, "--no-cascades --rawlog " + dir.string() + " --out " +
		             (kRawlogErrorsTmp / "out").string());
		EXPECT_EQ(r.code, 1) << app << ": " << r.err;
		EXPECT_EQ(lineCount(r.err), 1u) << app << ": " << r.err;
		EXPECT_NE(
		    r.err.find(
		        "cannot open rawlog " + dir.string() + ": is a directory"),
		    std::string::npos)
		    << app << ": " << r.err;
	}
	fs::remove_all(kRawlogErrorsTmp);
}

TEST(RawlogErrorsCli, TruncatedRawlogCountsAgreeWithTheMap)
{
	// A small room, two coarse sweeps; the second cut short.
	fs::create_directories(kRawlogErrorsTmp);
	const fs::path scene = kRawlogErrorsTmp / "room.yaml";
	std::ofstream(scene)
	    << "name: room\nbounds: [0, 0, 4, 4]\nobjects:\n"
	       "  - {label: wall, box: {center: [2, 0.05, 1], size: [4, 0.1, 2]}}\n"
	       "  - {label: wall, box: {center: [2, 3.95, 1], size: [4, 0.1, 2]}}\n"
	       "  - {label: wall, box: {center: [0.05, 2, 1], size: [0.1, 4, 2]}}\n"
	       "  - {label: wall, box: {center: [3.95, 2, 1], size: [0.1, 4, 2]}}\n"
	       "sensor: {phi: [-90, 90, 1], theta: [-15, 90, 1]}\n"
	       "trajectory: [[1.5, 2, 0], [2.5, 2, 0]]\n";
	const AppRun sim = runApp(
	    "semnav-sim", "--scene " + scene.string() + " --out " +
	                      (kRawlogErrorsTmp / "room").string());
	ASSERT_EQ(sim.code, 0) << sim.err;
	const fs::path rawlog = kRawlogErrorsTmp / "room" / "room.rawlog";
	fs::resize_file(rawlog, fs::file_size(rawlog) * 3 / 4);

	const AppRun r = runApp(
	    "semnav-map", "--no-cascades --json --rawlog " + rawlog.string() +
	                      " --out " + (kRawlogErrorsTmp / "map").string());
	EXPECT_EQ(r.code, 1) << r.err;
	const auto j = nlohmann::json::parse(r.out);
	const int mapped = j.at("sweeps").get<int>();
	const int incomplete = j.at("sweeps_skipped_incomplete").get<int>();
	EXPECT_GE(mapped, 1);
	EXPECT_EQ(incomplete, 1);
	const std::string last =
	    r.err.substr(r.err.rfind('\n', r.err.size() - 2) + 1);
	EXPECT_NE(
	    last.find("(" + std::to_string(mapped + incomplete) + " sweeps read)"),
	    std::string::npos)
	    << last;
	EXPECT_NE(
	    last.find(
	        "the map of " + std::to_string(mapped) + " of them written, " +
	        std::to_string(incomplete) + " incomplete left out"),
	    std::string::npos)
	    << last;
	fs::remove_all(kRawlogErrorsTmp);
}
