/* semnav: semantic navigation from tilting-laser sweeps */
// Pixel F1 per class against the simulator's ground truth (README
// "Perception", docs/perception.md "Accuracy"), each scene run as the
// README runs it:
//   semnav-sim --scene S --out D --seed 1
//   semnav-perceive --rawlog D/<name>.rawlog --out O --gt-dir D --json
// (SimulationRunner and PerceptionRun, the two apps' cores: rules and the
// shipped cascades). The figures are the same on every run (seeded
// simulation, deterministic perception). Each is asserted >= measured -
// kMargin.
#include <gtest/gtest.h>
#include <semnav/detection/CascadeDetector.h>
#include <semnav/sim/SceneLoader.h>
#include <semnav/sim/SimulationRunner.h>
#include <semnav/training/PerceptionRun.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <map>
#include <string>

#include "../TestPaths.h"

using namespace semnav;
namespace fs = std::filesystem;

namespace
{

/** A drop a few pixels' worth below the measured F1 (about a tenth of
 * the gap between a measured figure and the targets of issue 3). */
constexpr double kMargin = 0.015;

/** Simulates a scene (seed 1), perceives it as semnav-perceive does and
 * checks every F1 of `measured` within kMargin. */
void expectF1(
    const std::string& scenePath, const std::map<Label, double>& measured)
{
	const Scene scene =
	    SceneLoader::loadFile(test::kSourceDir + "/" + scenePath);
	const fs::path dir =
	    fs::temp_directory_path() /
	    ("semnav_percacc_" + scene.name + "_" + std::to_string(::getpid()));
	fs::remove_all(dir);
	const auto sim = SimulationRunner(scene, SimulationRunner::TOptions(), 1)
	                     .run((dir / "sim").string());
	PerceptionRun::Settings s;
	s.cascades = CascadeDetector::TOptions::fromIniFile(
	    test::kSourceDir + "/config/cascade.ini");
	s.rawlog = sim.rawlogPath;
	s.out = (dir / "perceive").string();
	s.gtDir = (dir / "sim").string();
	PerceptionRun run(s);
	run.run();
	fs::remove_all(dir);
	ASSERT_TRUE(run.scored());
	for (const auto& [label, f1] : measured)
	{
		const auto sc = run.labelScores().score(label);
		std::printf(
		    "[ MEASURED ] %s %-11s F1 %.4f (precision %.4f, recall %.4f, %zu "
		    "px)\n",
		    scene.name.c_str(), labelName(label).c_str(), sc.f1, sc.precision,
		    sc.recall, sc.groundTruthPixels);
		EXPECT_GT(sc.groundTruthPixels, 500u) << labelName(label);
		EXPECT_GE(sc.f1, f1 - kMargin)
		    << scene.name << " " << labelName(label) << ": precision "
		    << sc.precision << " recall " << sc.recall;
	}
}
}  // namespace

// The measured F1s (README and docs/perception.md tables).
TEST(PerceptionAccuracy, OfficeDataset)
{
	// With the detector's objects (docs/perception.md): stairs 0.982,
	// washbasin 0.980, wastebasket 0.766.
	expectF1(
	    "datasets/office/office.yaml", {{Label::Floor, 0.976},
	                                    {Label::Ceiling, 0.995},
	                                    {Label::Wall, 0.994},
	                                    {Label::Door, 0.948},
	                                    {Label::Stairs, 0.982},
	                                    {Label::Washbasin, 0.980},
	                                    {Label::Wastebasket, 0.766}});
}

TEST(PerceptionAccuracy, OutdoorDataset)
{
	expectF1(
	    "datasets/outdoor/outdoor.yaml", {{Label::Wall, 0.998},
	                                      {Label::Door, 0.974},
	                                      {Label::Sidewalk, 0.961},
	                                      {Label::Grass, 0.974}});
}

// Made after the rules were frozen (v2), scored once.
TEST(PerceptionAccuracy, LabScene)
{
	expectF1(
	    "tests/dataset/scenes/lab.yaml", {{Label::Floor, 0.964},
	                                      {Label::Ceiling, 0.997},
	                                      {Label::Wall, 0.957},
	                                      {Label::Door, 0.975}});
}

TEST(PerceptionAccuracy, ParkScene)
{
	expectF1(
	    "tests/dataset/scenes/park.yaml", {{Label::Wall, 0.970},
	                                       {Label::Door, 0.921},
	                                       {Label::Sidewalk, 0.922},
	                                       {Label::Grass, 0.946}});
}

// Made after the first freeze (v1), used to fix the rules (v2).
TEST(PerceptionAccuracy, CorridorScene)
{
	expectF1(
	    "tests/dataset/scenes/corridor.yaml", {{Label::Floor, 0.984},
	                                           {Label::Ceiling, 0.995},
	                                           {Label::Wall, 0.990},
	                                           {Label::Door, 0.862}});
}

TEST(PerceptionAccuracy, CampusScene)
{
	expectF1(
	    "tests/dataset/scenes/campus.yaml", {{Label::Wall, 0.995},
	                                         {Label::Door, 0.940},
	                                         {Label::Sidewalk, 0.919},
	                                         {Label::Grass, 0.951}});
}
