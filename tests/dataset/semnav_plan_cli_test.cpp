/* semnav: semantic navigation from tilting-laser sweeps */
// semnav-plan on a map built from the simulated office: JSON, PNG, grid
// export, and one-line errors with exit codes.
#include <gtest/gtest.h>
#include <semnav/map/MapIO.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/perception/PerceptionPipeline.h>
#include <semnav/scan/GroundTruthLog.h>
#include <semnav/scan/RawlogSweepReader.h>
#include <semnav/sim/SceneLoader.h>
#include <semnav/sim/SimulationRunner.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "AppRunner.h"

using namespace semnav;
namespace fs = std::filesystem;
using semnav::test::AppRun;
using semnav::test::lineCount;
using semnav::test::runApp;

namespace
{
AppRun runPlan(const std::string& args)
{
	return runApp("semnav-plan", args);
}

/** The office mapped with true poses from its first 5 stops. */
const fs::path& officeMapDir()
{
	static const fs::path dir = []
	{
		const fs::path d = fs::temp_directory_path() /
		                   ("semnav_planmap_" + std::to_string(::getpid()));
		fs::remove_all(d);
		Scene scene = SceneLoader::loadFile(
		    std::string(SEMNAV_SOURCE_DIR) + "/datasets/office/office.yaml");
		scene.trajectory.resize(5);
		const auto res =
		    SimulationRunner(scene, SimulationRunner::TOptions(), 1)
		        .run((d / "sim").string());
		const auto gt =
		    GroundTruthLog::forRawlog((d / "sim").string(), res.rawlogPath);
		SemanticMap map;
		PerceptionPipeline pipeline;
		RawlogSweepReader reader(res.rawlogPath);
		Sweep s;
		while (reader.next(s))
			map.insert(s, pipeline.process(s), gt.pose(s.index()));
		MapIO::save(map, (d / "map").string());
		return d / "map";
	}();
	return dir;
}

}  // namespace

TEST(SemnavPlanCli, PlansToTheNearestDoorWithPictureAndGrids)
{
	const fs::path out = officeMapDir().parent_path();
	const AppRun r = runPlan(
	    "--map " + officeMapDir().string() +
	    " --from 1.2,1.2 --goal door --json --png " +
	    (out / "plan.png").string() + " --export-grid " +
	    (out / "grid").string());
	ASSERT_EQ(r.code, 0) << r.err;
	EXPECT_TRUE(r.err.empty()) << r.err;
	const auto j = nlohmann::json::parse(r.out);
	EXPECT_TRUE(j.at("found").get<bool>());
	EXPECT_EQ(j.at("goal_label"), "door");
	EXPECT_GT(j.at("goal_object_id").get<int>(), 0);
	const auto& path = j.at("path");
	ASSERT_GE(path.size(), 2u);
	EXPECT_NEAR(path[0][0].get<double>(), 1.2, 0.05);
	EXPECT_NEAR(path[0][1].get<double>(), 1.2, 0.05);
	EXPECT_GE(
	    j.at("cost").get<double>(), j.at("length_m").get<double>() - 1e-9);
	EXPECT_GT(j.at("iterations").get<int>(), 0);
	EXPECT_TRUE(fs::file_size(out / "plan.png") > 1000);

	// grid export: .npy headers and the meta's path are consistent.
	std::ifstream u(out / "grid_u.npy", std::ios::binary);
	std::string head(10, '\0');
	u.read(head.data(), 10);
	EXPECT_EQ(head.substr(0, 6), "\x93NUMPY");
	const std::size_t hlen = static_cast<unsigned char>(head[8]) |
	                         (static_cast<unsigned char>(head[9]) << 8);
	std::string dict(hlen, '\0');
	u.read(dict.data(), static_cast<std::streamsize>(hlen));
	EXPECT_NE(dict.find("'descr': '<f4'"), std::string::npos) << dict;
	EXPECT_EQ((10 + hlen) % 64, 0u);
	std::ifstream metaFile(out / "grid_meta.json");
	const auto meta = nlohmann::json::parse(metaFile);
	EXPECT_EQ(meta.at("path").size(), path.size());
	EXPECT_EQ(meta.at("start"), meta.at("path")[0]);
	const int rows = meta.at("path")[0][0], cols = meta.at("path")[0][1];
	EXPECT_NE(dict.find("'shape': ("), std::string::npos);
	EXPECT_GE(rows, 0);
	EXPECT_GE(cols, 0);
	std::vector<float> uv(fs::file_size(out / "grid_u.npy") - 10 - hlen);
	u.read(
	    reinterpret_cast<char*>(uv.data()),
	    static_cast<std::streamsize>(uv.size()));
	EXPECT_TRUE(std::any_of(
	    uv.begin(), uv.end(), [](float v) { return std::isinf(v); }))
	    << "blocked cells are +inf";
}

TEST(SemnavPlanCli, ErrorsAreOneLineWithExitCodes)
{
	const std::string map = "--map " + officeMapDir().string();
	struct Case
	{
		std::string args, needle;
		int code;
	};
	const Case cases[] = {
	    {map + " --from 1.2,1.2 --goal trashcan", "known:", 1},
	    {map + " --from 1.2,1.2 --goal stairs_nope", "unknown label", 1},
	    {map + " --from 1.2,1.2 --goal washbasin", "no washbasin", 1},
	    {map + " --from 500,500 --goal door", "outside", 1},
	    {map + " --from 1.2 --goal door", "--from", 2},
	    {map + " --from 1.2,1.2", "exactly one", 2},
	    {map + " --from 1.2,1.2 --goal \"$(printf 'so\\001\\377fa')\"",
	     "unknown label 'so\\x01\\xFFfa'", 1},
	    {map + " --from \"$(printf '1\\033[2J,2')\" --goal door",
	     "got '1\\x1B[2J,2'", 2},
	    {map + " --from 1.2,1.2 --goal door --profile fastest",
	     "--profile: unknown cost profile 'fastest'", 2},
	    {"--map /nonexistent --from 1,1 --goal door", "/nonexistent", 1},
	};
	for (const auto& c : cases)
	{
		const AppRun r = runPlan(c.args);
		EXPECT_EQ(r.code, c.code) << c.args << ": " << r.err;
		EXPECT_EQ(lineCount(r.err), 1u) << c.args << ": " << r.err;
		EXPECT_NE(r.err.find(c.needle), std::string::npos)
		    << c.args << ": " << r.err;
	}
}

TEST(SemnavPlanCli, ObjectsAreTheOnesTheSummaryReports)
{
	// The office map with a 4 cm "door" (a wall fragment) added: a
	// candidate, not an object.
	SemanticMap map;
	MapIO::load(officeMapDir().string(), map);
	const int tiny =
	    map.addInstance(Label::Door, {2.0, 1.0, 0.40}, {2.04, 1.1, 0.44});
	ASSERT_FALSE(map.reported(map.instance(tiny)));
	const fs::path dir = officeMapDir().parent_path() / "map_with_candidate";
	MapIO::save(map, dir.string());
	const AppRun r = runPlan(
	    "--map " + dir.string() + " --from 1.2,1.2 --object " +
	    std::to_string(tiny));
	EXPECT_EQ(r.code, 1) << r.err;
	EXPECT_EQ(lineCount(r.err), 1u) << r.err;
	EXPECT_NE(
	    r.err.find(
	        "the map has no object " + std::to_string(tiny) + " (objects: "),
	    std::string::npos)
	    << r.err;
}
