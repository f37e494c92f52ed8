/* semnav: semantic navigation from tilting-laser sweeps */
// semnav-map --poses pf on a simulated drift run: the summary's
// localization block, the shipped localization config, bad config.
#include <gtest/gtest.h>
#include <semnav/sim/SceneLoader.h>
#include <semnav/sim/SimulationRunner.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "AppRunner.h"

using namespace semnav;
namespace fs = std::filesystem;

namespace
{
const fs::path& simDir()
{
	static const fs::path d = []
	{
		const fs::path dir =
		    fs::temp_directory_path() /
		    ("semnav_mapcli_loc_" + std::to_string(::getpid()));
		fs::remove_all(dir);
		const Scene scene = SceneLoader::loadFile(
		    std::string(SEMNAV_SOURCE_DIR) +
		    "/datasets/localization/rooms.yaml");
		SimulationRunner(scene, SimulationRunner::TOptions(), 1)
		    .run(dir.string());
		return dir;
	}();
	return d;
}
}  // namespace

TEST(SemnavMapLocalization, PfPosesReportLocalizationErrors)
{
	const fs::path out = simDir() / "map-pf";
	const std::string src = SEMNAV_SOURCE_DIR;
	const auto r = test::runApp(
	    "semnav-map", "--rawlog " + (simDir() / "rooms.rawlog").string() +
	                      " --out " + out.string() + " --poses pf --gt-dir " +
	                      simDir().string() + " --loc-config " + src +
	                      "/config/localization.ini --json");
	ASSERT_EQ(r.code, 0) << r.err;
	const auto j = nlohmann::json::parse(r.out);
	ASSERT_TRUE(j.contains("localization"));
	const auto& l = j["localization"];
	for (const char* k :
	     {"rmse_xy_m", "final_yaw_err_deg", "max_yaw_err_deg",
	      "odometry_final_yaw_err_deg", "odometry_rmse_xy_m"})
		EXPECT_TRUE(l.contains(k)) << k;
	EXPECT_GE(l["odometry_final_yaw_err_deg"].get<double>(), 30.0);
	EXPECT_LE(l["final_yaw_err_deg"].get<double>(), 2.0);
	EXPECT_LE(l["rmse_xy_m"].get<double>(), 0.08);
	EXPECT_TRUE(fs::exists(out / "map.yaml"));
}

TEST(SemnavMapLocalization, MainDirectionsOffIsAConfigSwitch)
{
	const fs::path cfg = simDir() / "off.ini";
	{
		std::ofstream f(cfg);
		f << "[Localizer]\nmain_directions = false\n";
	}
	const auto r = test::runApp(
	    "semnav-map", "--rawlog " + (simDir() / "rooms.rawlog").string() +
	                      " --out " + (simDir() / "map-off").string() +
	                      " --poses pf --gt-dir " + simDir().string() +
	                      " --loc-config " + cfg.string() + " --json");
	ASSERT_EQ(r.code, 0) << r.err;
	const auto l = nlohmann::json::parse(r.out)["localization"];
	// Still localized, but the heading is no longer pinned to < 0.5 deg.
	EXPECT_LT(l["final_yaw_err_deg"].get<double>(), 10.0);
	EXPECT_GT(l["max_yaw_err_deg"].get<double>(), 0.5);
}

TEST(SemnavMapLocalization, BadLocalizationConfigIsOneLineError)
{
	const fs::path cfg = simDir() / "bad.ini";
	{
		std::ofstream f(cfg);
		f << "[Localizer]\nmain_direction = false\n";
	}
	const auto r = test::runApp(
	    "semnav-map", "--rawlog " + (simDir() / "rooms.rawlog").string() +
	                      " --out " + (simDir() / "map-bad").string() +
	                      " --poses pf --loc-config " + cfg.string());
	EXPECT_EQ(r.code, 1);
	EXPECT_NE(r.err.find("main_direction"), std::string::npos) << r.err;
	EXPECT_EQ(test::lineCount(r.err), 1u) << r.err;
}
