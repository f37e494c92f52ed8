/* semnav: semantic navigation from tilting-laser sweeps */
// The semnav-perceive command line: exit codes, one-line errors, --json,
// the PNGs per sweep, scoring against semnav-sim's ground truth, and a
// corrupt rawlog (outputs for the good sweeps, then one line, exit 1).
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "../TestPaths.h"
#include "../common/ThreeDtkData.h"
#include "AppRunner.h"

namespace fs = std::filesystem;
using semnav::test::AppRun;
using semnav::test::lineCount;
using semnav::test::runApp;

namespace
{
const fs::path kPerceiveCliTmp =
    fs::temp_directory_path() /
    ("semnav_perceive_cli_" + std::to_string(::getpid()));

/** The outdoor dataset simulated once (7 sweeps). */
const fs::path& outdoorSim()
{
	static const fs::path dir = []
	{
		const fs::path d = kPerceiveCliTmp / "sim";
		const AppRun r = runApp(
		    "semnav-sim", "--scene " + semnav::test::kSourceDir +
		                      "/datasets/outdoor/outdoor.yaml --out " +
		                      d.string() + " --seed 1");
		EXPECT_EQ(r.code, 0) << r.err;
		return d;
	}();
	return dir;
}

class SemnavPerceiveCli : public ::testing::Test
{
protected:
	static void TearDownTestSuite() { fs::remove_all(kPerceiveCliTmp); }
};
}  // namespace

TEST_F(SemnavPerceiveCli, BadUsageIsExit2WithOneLine)
{
	for (const std::string args :
	     {"", "--out /tmp/x", "--rawlog a --3dtk b --out /tmp/x", "--rawlog a",
	      "--bogus"})
	{
		const AppRun r = runApp("semnav-perceive", args);
		EXPECT_EQ(r.code, 2) << args;
		EXPECT_EQ(lineCount(r.err), 1u) << args << ": " << r.err;
		EXPECT_EQ(r.err.rfind("semnav-perceive: ", 0), 0u) << r.err;
		EXPECT_TRUE(r.out.empty());
	}
	EXPECT_EQ(runApp("semnav-perceive", "--help").code, 0);
}

TEST_F(SemnavPerceiveCli, ErrorsAreExit1WithOneLine)
{
	AppRun r = runApp(
	    "semnav-perceive", "--rawlog /nonexistent.rawlog --out " +
	                           (kPerceiveCliTmp / "e").string());
	EXPECT_EQ(r.code, 1);
	EXPECT_EQ(lineCount(r.err), 1u) << r.err;
	EXPECT_NE(r.err.find("/nonexistent.rawlog"), std::string::npos);

	const fs::path ini = kPerceiveCliTmp / "bad.ini";
	fs::create_directories(kPerceiveCliTmp);
	std::ofstream(ini) << "[RuleClassifier]\ndoor_min_width_m = -1\n";
	r = runApp(
	    "semnav-perceive",
	    "--rawlog " + (outdoorSim() / "outdoor.rawlog").string() + " --out " +
	        (kPerceiveCliTmp / "e").string() + " --config " + ini.string());
	EXPECT_EQ(r.code, 1);
	EXPECT_EQ(lineCount(r.err), 1u) << r.err;
	EXPECT_NE(r.err.find("door_min_width_m"), std::string::npos) << r.err;
}

TEST_F(SemnavPerceiveCli, ScoresAgainstGroundTruthAsJson)
{
	const fs::path out = kPerceiveCliTmp / "out";
	const AppRun r = runApp(
	    "semnav-perceive",
	    "--rawlog " + (outdoorSim() / "outdoor.rawlog").string() + " --out " +
	        out.string() + " --gt-dir " + outdoorSim().string() + " --config " +
	        semnav::test::kSourceDir + "/config/perception.ini --json");
	ASSERT_EQ(r.code, 0) << r.err;
	const auto j = nlohmann::json::parse(r.out);
	EXPECT_EQ(j.at("sweeps").get<int>(), 7);
	EXPECT_GT(j.at("ms_per_sweep_median").get<double>(), 0.0);
	EXPECT_TRUE(j.at("objects").is_object());
	const auto& classes = j.at("classes");
	for (const char* l : {"wall", "door", "sidewalk", "grass"})
	{
		ASSERT_TRUE(classes.contains(l)) << l;
		const auto& c = classes.at(l);
		for (const char* k : {"precision", "recall", "f1", "pixels"})
			EXPECT_TRUE(c.contains(k));
		EXPECT_GT(c.at("pixels").get<long>(), 0);
		EXPECT_GT(c.at("f1").get<double>(), 0.8) << l;
	}
	EXPECT_FALSE(classes.contains("floor"))
	    << "outdoor: no floor in truth nor output";
	// Four images per sweep, the sweep's size (labels and gt with a legend).
	for (int i = 0; i < 7; i++)
	{
		char name[32];
		std::snprintf(name, sizeof(name), "sweep_%04d", i);
		const cv::Mat n =
		    cv::imread((out / (std::string(name) + "_normal.png")).string());
		ASSERT_FALSE(n.empty()) << name;
		EXPECT_EQ(n.rows, 211);
		EXPECT_EQ(n.cols, 361);
		const cv::Mat s =
		    cv::imread((out / (std::string(name) + "_segments.png")).string());
		EXPECT_EQ(s.size(), n.size());
		const cv::Mat l =
		    cv::imread((out / (std::string(name) + "_labels.png")).string());
		EXPECT_GT(l.rows, n.rows);  // legend below
		EXPECT_TRUE(fs::exists(out / (std::string(name) + "_gt.png")));
	}
	// No temporary files left behind by the atomic writes.
	for (const auto& e : fs::directory_iterator(out))
		EXPECT_EQ(e.path().extension(), ".png") << e.path();
}

TEST_F(SemnavPerceiveCli, CorruptRawlogWritesTheGoodSweepsThenFails)
{
	const fs::path src = outdoorSim() / "outdoor.rawlog";
	const fs::path bad = kPerceiveCliTmp / "cut.rawlog";
	{
		std::ifstream in(src, std::ios::binary);
		std::string all((std::istreambuf_iterator<char>(in)), {});
		std::ofstream(bad, std::ios::binary) << all.substr(0, all.size() / 2);
	}
	const fs::path out = kPerceiveCliTmp / "cut";
	const AppRun r = runApp(
	    "semnav-perceive",
	    "--rawlog " + bad.string() + " --out " + out.string());
	EXPECT_EQ(r.code, 1);
	EXPECT_EQ(r.err.rfind("semnav-perceive: "), r.err.find("semnav-perceive: "))
	    << "one error line: " << r.err;
	EXPECT_NE(r.err.find("cut.rawlog"), std::string::npos) << r.err;
	std::size_t labels = 0;
	for (const auto& e : fs::directory_iterator(out))
		labels += e.path().string().find("_labels.png") != std::string::npos;
	EXPECT_GE(labels, 2u);
	EXPECT_LT(labels, 7u);
}

TEST_F(SemnavPerceiveCli, ThreeDtkScan)
{
	SKIP_WITHOUT_3DTK("scan000.3d");
	const fs::path scan = semnav::test::kThreeDtkDir / "scan000.3d";
	const fs::path out = kPerceiveCliTmp / "3dtk";
	const AppRun r = runApp(
	    "semnav-perceive",
	    "--3dtk " + scan.string() + " --out " + out.string() + " --json");
	ASSERT_EQ(r.code, 0) << r.err;
	EXPECT_EQ(nlohmann::json::parse(r.out).at("sweeps").get<int>(), 1);
	const cv::Mat n = cv::imread((out / "sweep_0000_normal.png").string());
	EXPECT_EQ(n.rows, 226);
	EXPECT_EQ(n.cols, 360);
}

TEST_F(SemnavPerceiveCli, DetectsObjectsByDefaultNotWithNoCascades)
{
	const std::string in = "--rawlog " +
	                       (outdoorSim() / "outdoor.rawlog").string() +
	                       " --gt-dir " + outdoorSim().string() + " --json";
	const fs::path on = kPerceiveCliTmp / "cascades-on",
	               off = kPerceiveCliTmp / "cascades-off";
	const AppRun a = runApp("semnav-perceive", in + " --out " + on.string());
	ASSERT_EQ(a.code, 0) << a.err;
	const auto ja = nlohmann::json::parse(a.out);
	for (const char* l : {"washbasin", "wastebasket", "stairs"})
		EXPECT_TRUE(ja.at("objects").contains(l)) << l;
	EXPECT_TRUE(ja.contains("ms_detection_per_sweep_median"));
	EXPECT_TRUE(fs::exists(on / "sweep_0000_detections.png"));

	const AppRun b = runApp(
	    "semnav-perceive", in + " --out " + off.string() + " --no-cascades");
	ASSERT_EQ(b.code, 0) << b.err;
	const auto jb = nlohmann::json::parse(b.out);
	EXPECT_TRUE(jb.at("objects").empty());
	EXPECT_FALSE(jb.contains("ms_detection_per_sweep_median"));
	EXPECT_FALSE(fs::exists(off / "sweep_0000_detections.png"));
}
