/* semnav: semantic navigation from tilting-laser sweeps */
// The cascade command lines end to end on one simulated held-out scene:
// semnav-train-cascade (exit codes, one-line errors, --json, same seed ->
// same XML bytes, the XML loads in cv::CascadeClassifier), semnav-detect
// and semnav-perceive --cascades (the "objects" scores). Training is tiny
// here (2 stages, 60 positives); scripts/train-cascades makes the real ones.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/objdetect.hpp>
#include <regex>
#include <sstream>
#include <string>

#include "../TestPaths.h"
#include "AppRunner.h"

namespace fs = std::filesystem;
using semnav::test::AppRun;
using semnav::test::lineCount;
using semnav::test::runApp;

namespace
{
const fs::path kCascadeCliTmp =
    fs::temp_directory_path() /
    ("semnav_cascade_cli_" + std::to_string(::getpid()));

/** test_a simulated once (26 sweeps). */
const fs::path& sim()
{
	static const fs::path dir = []
	{
		const fs::path d = kCascadeCliTmp / "test_a";
		const AppRun r = runApp(
		    "semnav-sim", "--scene " + semnav::test::kSourceDir +
		                      "/datasets/cascade-scenes/test_a.yaml --out " +
		                      d.string() + " --seed 1");
		EXPECT_EQ(r.code, 0) << r.err;
		return d;
	}();
	return dir;
}

/** A small training configuration whose cascade goes to kCascadeCliTmp. */
std::string config()
{
	const fs::path ini = kCascadeCliTmp / "tiny.ini";
	if (!fs::exists(ini))
	{
		std::ofstream o(ini);
		o << "[CascadeDetector]\nclasses = washbasin\n"
		     "[CascadeDetector.washbasin]\ncascade = washbasin.xml\n"
		     "far_upscale = 0\nmin_neighbors = 1\n"
		     "[SampleGenerator]\npositives = 60\n"
		     "[CascadeTrainer]\nnum_stages = 2\nnegatives_per_stage = 120\n"
		     "max_weak_count = 10\nround_feature_fraction = 0.05\n"
		     "target_false_alarm = 1e-9\n";
	}
	return ini.string();
}

std::string readFile(const fs::path& p)
{
	std::ifstream in(p, std::ios::binary);
	std::ostringstream s;
	s << in.rdbuf();
	return s.str();
}

class SemnavCascadeCli : public ::testing::Test
{
protected:
	static void SetUpTestSuite() { fs::create_directories(kCascadeCliTmp); }
	static void TearDownTestSuite() { fs::remove_all(kCascadeCliTmp); }
};
}  // namespace

TEST_F(SemnavCascadeCli, BadUsageIsExit2AndErrorsExit1WithOneLine)
{
	for (const std::string args :
	     {"", "--label washbasin --out x.xml", "--label washbasin --datasets d",
	      "--label washbasin --datasets d --out x.xml --seed -3", "--bogus"})
	{
		const AppRun r = runApp("semnav-train-cascade", args);
		EXPECT_EQ(r.code, 2) << args;
		EXPECT_EQ(lineCount(r.err), 1u) << args << ": " << r.err;
	}
	const AppRun help = runApp("semnav-train-cascade", "--help");
	EXPECT_EQ(help.code, 0);
	for (const std::string args :
	     {"--label sofa --datasets " + sim().string() + " --out " +
	          (kCascadeCliTmp / "x.xml").string(),
	      "--label washbasin --datasets /nonexistent --out " +
	          (kCascadeCliTmp / "x.xml").string(),
	      "--label washbasin --datasets " + sim().string() + " --out " +
	          (kCascadeCliTmp / "x.xml").string() +
	          " --config /nonexistent.ini"})
	{
		const AppRun r = runApp("semnav-train-cascade", args);
		EXPECT_EQ(r.code, 1) << args;
		EXPECT_EQ(lineCount(r.err), 1u) << args << ": " << r.err;
	}
	EXPECT_FALSE(fs::exists(kCascadeCliTmp / "x.xml"));
	const AppRun d = runApp("semnav-detect", "--datasets " + sim().string());
	EXPECT_EQ(d.code, 2);
}

TEST_F(SemnavCascadeCli, TrainDetectAndPerceive)
{
	const std::string out = (kCascadeCliTmp / "washbasin.xml").string();
	const std::string args = "--label washbasin --datasets " + sim().string() +
	                         " --out " + out + " --seed 5 --config " + config();
	const AppRun r = runApp("semnav-train-cascade", args + " --json");
	ASSERT_EQ(r.code, 0) << r.err;
	const auto j = nlohmann::json::parse(r.out);
	EXPECT_EQ(j.at("label"), "washbasin");
	EXPECT_EQ(j.at("stages"), 2);
	EXPECT_EQ(j.at("positives"), 60);
	EXPECT_TRUE(j.at("tilted_features").is_boolean());
	EXPECT_GT(j.at("seconds").get<double>(), 0.0);
	EXPECT_EQ(j.at("stage_details").size(), 2u);
	const std::string first = readFile(out);
	EXPECT_NE(
	    first.find("semnav-train-cascade --label washbasin"), std::string::npos)
	    << "the XML says how it was made";
	cv::CascadeClassifier cc;
	EXPECT_TRUE(cc.load(out));
	// Same command, same bytes.
	const AppRun again = runApp("semnav-train-cascade", args);
	ASSERT_EQ(again.code, 0) << again.err;
	EXPECT_EQ(readFile(out), first);
	// The cascade accepts the very samples it was trained on (two stages,
	// 60 positives: each stage keeps them all).
	const AppRun score = runApp(
	    "semnav-train-cascade", "--label washbasin --datasets " +
	                                sim().string() + " --seed 5 --config " +
	                                config() + " --score-positives " + out +
	                                " --json");
	ASSERT_EQ(score.code, 0) << score.err;
	const auto sj = nlohmann::json::parse(score.out);
	EXPECT_EQ(sj.at("positives"), 60);
	EXPECT_EQ(
	    sj.at("accepted").get<int>() + sj.at("low_contrast").get<int>(), 60);

	const AppRun det = runApp(
	    "semnav-detect",
	    "--datasets " + sim().string() + " --config " + config() + " --json");
	ASSERT_EQ(det.code, 0) << det.err;
	const auto dj = nlohmann::json::parse(det.out);
	EXPECT_EQ(dj.at("sweeps"), 26);
	for (const char* k : {"tp", "fp", "fn", "precision", "recall"})
		EXPECT_TRUE(dj.at("objects").at("washbasin").contains(k)) << k;
	for (const char* k : {"tp", "fp", "fn", "excluded", "recall"})
		EXPECT_TRUE(dj.at("objects_recognisable").at("washbasin").contains(k))
		    << k;
	// Counted by distinct points: the excluded objects were counted by
	// pixels, the same detections are scored.
	const auto& dp = dj.at("objects_distinct_points").at("washbasin");
	const auto& px = dj.at("objects").at("washbasin");
	EXPECT_EQ(
	    dp.at("tp").get<int>() + dp.at("fn").get<int>() +
	        dp.at("excluded").get<int>(),
	    px.at("tp").get<int>() + px.at("fn").get<int>());
	EXPECT_EQ(dp.at("fp"), px.at("fp"));
	// Where the objects are lost: each step keeps at most the one before,
	// and a true positive is an object an accepted candidate reaches.
	const auto& funnel = dj.at("funnel").at("washbasin");
	const auto& wb = dj.at("objects").at("washbasin");
	EXPECT_EQ(
	    funnel.at("counted").get<int>(),
	    wb.at("tp").get<int>() + wb.at("fn").get<int>());
	EXPECT_GE(funnel.at("counted"), funnel.at("reached"));
	EXPECT_GE(funnel.at("reached"), funnel.at("sized"));
	EXPECT_GE(funnel.at("sized"), funnel.at("accepted"));
	EXPECT_GE(funnel.at("accepted"), wb.at("tp"));
	EXPECT_GT(wb.at("tp").get<int>(), 0);

	const std::string rawlog = (sim() / "test_a.rawlog").string();
	const AppRun p = runApp(
	    "semnav-perceive", "--rawlog " + rawlog + " --gt-dir " +
	                           sim().string() + " --out " +
	                           (kCascadeCliTmp / "perceive").string() +
	                           " --cascades " + config() + " --json");
	ASSERT_EQ(p.code, 0) << p.err;
	const auto pj = nlohmann::json::parse(p.out);
	const auto& o = pj.at("objects").at("washbasin");
	for (const char* k : {"tp", "fp", "fn", "precision", "recall"})
		EXPECT_TRUE(o.contains(k)) << k;
	// Same detector, same scene, same rule: the same counts as semnav-detect.
	EXPECT_EQ(o.at("tp"), dj.at("objects").at("washbasin").at("tp"));
	EXPECT_EQ(o.at("fn"), dj.at("objects").at("washbasin").at("fn"));
	EXPECT_TRUE(
	    fs::exists(kCascadeCliTmp / "perceive" / "sweep_0000_detections.png"));
}

TEST_F(SemnavCascadeCli, TrainShapeModelAndDetectWithIt)
{
	// The shipped washbasin cascade's candidates in test_a: a shape model,
	// the same bytes for the same seed, and one the detector loads.
	const fs::path ini = kCascadeCliTmp / "shape.ini";
	{
		std::ofstream o(ini);
		o << "[CascadeDetector]\nclasses = washbasin\nrange_scales = true\n"
		     "[CascadeDetector.washbasin]\ncascade = "
		  << semnav::test::kSourceDir
		  << "/datasets/cascades/washbasin.xml\n"
		     "shape_model = washbasin-shape.xml.gz\nmax_stages = 14\n"
		     "min_neighbors = 1\n";
	}
	const std::string out =
	    (kCascadeCliTmp / "washbasin-shape.xml.gz").string();
	const std::string common = "--label washbasin --datasets " +
	                           sim().string() + " --config " + ini.string() +
	                           " --out " + out + " --trees 20 --seed 3";
	const std::string args = common + " --max-samples 2000";
	// The config names a shape model not written yet: training needs none.
	const AppRun r = runApp("semnav-train-shape", args + " --json");
	ASSERT_EQ(r.code, 0) << r.err;
	const auto j = nlohmann::json::parse(r.out);
	EXPECT_EQ(j.at("sweeps"), 26);
	EXPECT_GT(j.at("objects").get<int>(), 0);
	EXPECT_GT(j.at("others").get<int>(), 0);
	EXPECT_LE(j.at("objects").get<int>() + j.at("others").get<int>(), 2000);
	const std::string first = readFile(out);
	const AppRun again = runApp("semnav-train-shape", args);
	ASSERT_EQ(again.code, 0) << again.err;
	EXPECT_EQ(readFile(out), first);
	// --min-purity: object samples whose measured points are mostly another
	// object are left out as ambiguous, nothing else changes.
	// Every sample counted (no subset), with these options.
	const auto samplesWith = [&](const std::string& options)
	{
		const AppRun p = runApp(
		    "semnav-train-shape",
		    common + " --max-samples 0 --max-objects-per-other 0 " + options +
		        " --json");
		EXPECT_EQ(p.code, 0) << p.err;
		return nlohmann::json::parse(p.out);
	};
	const auto all = samplesWith("--min-purity 0"),
	           pure = samplesWith("--min-purity 0.9");
	EXPECT_EQ(all.at("impure"), 0);
	EXPECT_GT(pure.at("impure").get<int>(), 0);
	EXPECT_EQ(
	    pure.at("objects").get<int>() + pure.at("impure").get<int>(),
	    all.at("objects").get<int>());
	EXPECT_EQ(
	    pure.at("ambiguous").get<int>(),
	    all.at("ambiguous").get<int>() + pure.at("impure").get<int>());
	EXPECT_EQ(pure.at("others"), all.at("others"));
	EXPECT_EQ(runApp("semnav-train-shape", args + " --min-purity 1.5").code, 2);
	// --object-iou: a lower bar makes some ambiguous boxes objects; the
	// others stay.
	const auto lj = samplesWith("--object-iou 0.15");
	EXPECT_GT(lj.at("objects").get<int>(), all.at("objects").get<int>());
	EXPECT_EQ(
	    lj.at("objects").get<int>() + lj.at("ambiguous").get<int>(),
	    all.at("objects").get<int>() + all.at("ambiguous").get<int>());
	EXPECT_EQ(lj.at("others"), all.at("others"));
	EXPECT_EQ(
	    runApp("semnav-train-shape", args + " --object-iou 0.05").code, 2);
	// --range-scale-slack: the config's value gives the same samples, a
	// wider gate more windows, so more candidates.
	const auto total = [](const nlohmann::json& x)
	{
		return x.at("objects").get<int>() + x.at("others").get<int>() +
		       x.at("ambiguous").get<int>();
	};
	const auto same = samplesWith("--range-scale-slack 1.3"),
	           wide = samplesWith("--range-scale-slack 3");
	EXPECT_EQ(same, all);
	EXPECT_GT(total(wide), total(all));
	EXPECT_EQ(
	    runApp("semnav-train-shape", args + " --range-scale-slack 0.5").code,
	    2);
	// Segments measured as the shipped forests learnt them (without
	// segment_range_window): the same sweeps, candidates of their own.
	const auto uj = samplesWith("--without-segment-window");
	EXPECT_EQ(uj.at("sweeps"), 26);
	EXPECT_GT(uj.at("objects").get<int>(), 0);
	const AppRun det = runApp(
	    "semnav-detect", "--datasets " + sim().string() + " --config " +
	                         ini.string() + " --json");
	ASSERT_EQ(det.code, 0) << det.err;
	const auto dj = nlohmann::json::parse(det.out);
	EXPECT_GT(dj.at("objects").at("washbasin").at("tp"), 0);
	// --misses: a line per counted object no accepted detection matches
	// (at most the false negatives) and per false detection, each saying
	// where it is and what the nearest candidate became.
	const AppRun misses = runApp(
	    "semnav-detect", "--datasets " + sim().string() + " --config " +
	                         ini.string() + " --misses");
	ASSERT_EQ(misses.code, 0) << misses.err;
	std::istringstream lines(misses.err);
	int missLines = 0, falseLines = 0;
	// ...and which ground-truth objects its points lie on.
	const std::regex on("on [0-9]+ % [a-z]+ #[0-9]+");
	const std::regex distinctCells(
	    "([0-9]+) px \\(([0-9]+) distinct 2 cm cells\\)");
	for (std::string line; std::getline(lines, line);)
	{
		if (line.rfind("miss ", 0) == 0)
		{
			missLines++;
			EXPECT_NE(line.find("nearest candidate IoU"), std::string::npos)
			    << line;
			// ...and the best of those whose points are mostly the object's.
			EXPECT_NE(
			    line.find("of those mostly on it, IoU"), std::string::npos)
			    << line;
			// Its distinct points: 1 .. its pixels.
			std::smatch cells;
			ASSERT_TRUE(std::regex_search(line, cells, distinctCells)) << line;
			EXPECT_GE(std::stoi(cells[2]), 1) << line;
			EXPECT_LE(std::stoi(cells[2]), std::stoi(cells[1])) << line;
			if (line.find("no measured candidate") == std::string::npos)
				EXPECT_TRUE(std::regex_search(line, on)) << line;
		}
		if (line.rfind("false ", 0) == 0)
		{
			falseLines++;
			EXPECT_TRUE(std::regex_search(line, on)) << line;
		}
	}
	EXPECT_LE(missLines, dj.at("objects").at("washbasin").at("fn").get<int>());
	EXPECT_GT(missLines + falseLines, 0);
	// Bad input: one line, exit 1 (unknown label, missing dataset, a
	// corrupt model named by the config); bad usage: exit 2.
	std::ofstream(kCascadeCliTmp / "washbasin-shape.xml.gz") << "not a forest";
	const AppRun corrupt = runApp(
	    "semnav-detect",
	    "--datasets " + sim().string() + " --config " + ini.string());
	EXPECT_EQ(corrupt.code, 1);
	EXPECT_EQ(lineCount(corrupt.err), 1u) << corrupt.err;
	EXPECT_NE(corrupt.err.find("washbasin-shape.xml.gz"), std::string::npos);
	for (const std::string bad :
	     {"--label sofa --datasets " + sim().string(),
	      std::string("--label washbasin --datasets /nonexistent")})
	{
		const AppRun e = runApp(
		    "semnav-train-shape", bad + " --config " + ini.string() +
		                              " --out " +
		                              (kCascadeCliTmp / "x.xml.gz").string());
		EXPECT_EQ(e.code, 1) << bad;
		EXPECT_EQ(lineCount(e.err), 1u) << bad << ": " << e.err;
	}
	EXPECT_FALSE(fs::exists(kCascadeCliTmp / "x.xml.gz"));
	EXPECT_EQ(runApp("semnav-train-shape", "--label washbasin").code, 2);
}
