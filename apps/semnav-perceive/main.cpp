/* semnav: semantic navigation from tilting-laser sweeps */
// semnav-perceive: normal image, segmentation, rule-based labels and
// detected objects of every sweep of a rawlog or a 3DTK scan, optionally
// scored against semnav-sim's ground truth (docs/design.md, "Apps").
#include <semnav/common/CascadeArgs.h>
#include <semnav/common/CommandLine.h>
#include <semnav/common/IniSections.h>
#include <semnav/common/Percentile.h>
#include <semnav/common/ProgressBar.h>
#include <semnav/training/PerceptionRun.h>
#include <semnav/training/ScoreJson.h>

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>

namespace
{
void printJson(const semnav::PerceptionRun& r)
{
	nlohmann::json j;
	j["sweeps"] = r.sweeps();
	j["ms_per_sweep_median"] = semnav::median(r.msRules());
	j["classes"] = nlohmann::json::object();
	j["objects"] = nlohmann::json::object();
	if (r.scored())
	{
		j["classes"] = semnav::labelScoresJson(r.labelScores());
		// Object detection (issue 4's rule: an object counts when >= 150 of
		// its pixels are visible; IoU >= 0.3 with a not yet matched object
		// of the label is a true positive).
		for (const auto l : r.objectLabels())
			j["objects"][semnav::labelName(l)] =
			    semnav::objectScoreJson(r.objectScores().score(l));
	}
	if (r.detectsObjects())
		j["ms_detection_per_sweep_median"] = semnav::median(r.msDetection());
	std::cout << j.dump() << std::endl;
}

void printText(const semnav::PerceptionRun& r, const std::string& out)
{
	std::cout << r.sweeps() << " sweeps -> " << out << " (median "
	          << semnav::median(r.msRules()) << " ms per sweep)\n";
	if (!r.scored()) return;
	std::printf(
	    "%-12s %9s %9s %9s %10s\n", "label", "precision", "recall", "f1",
	    "gt_pixels");
	for (const auto l : r.labelScores().labelsSeen())
	{
		const auto s = r.labelScores().score(l);
		std::printf(
		    "%-12s %9.4f %9.4f %9.4f %10zu\n", semnav::labelName(l).c_str(),
		    s.precision, s.recall, s.f1, s.groundTruthPixels);
	}
	for (const auto l : r.objectLabels())
	{
		const auto s = r.objectScores().score(l);
		std::printf(
		    "objects %-12s tp %zu fp %zu fn %zu precision %.3f recall %.3f\n",
		    semnav::labelName(l).c_str(), s.tp, s.fp, s.fn, s.precision,
		    s.recall);
	}
}
}  // namespace

int main(int argc, char** argv)
{
	semnav::CommandLine cli(
	    "semnav-perceive",
	    "Computes the normal image, the range segmentation, the rule-based "
	    "labels (floor, ceiling, wall, door, sidewalk, grass, obstacle) and "
	    "the detected washbasins, wastebaskets and stairs of every sweep and "
	    "writes <out>/sweep_NNNN_normal.png, _segments.png, _labels.png and "
	    "_detections.png (shown as seen from the robot: up is up, the "
	    "robot's left on the left). With --gt-dir, scores pixel "
	    "precision/recall/F1 per label (valid-range pixels) and the objects "
	    "per class, and writes the ground truth in the same colours as "
	    "_gt.png.");
	auto& cmd = cli.cmd();
	TCLAP::ValueArg<std::string> argRawlog(
	    "", "rawlog", "Input rawlog (tilting 2D laser); this or --3dtk", false,
	    "", "R", cmd);
	TCLAP::ValueArg<std::string> argTdtk(
	    "", "3dtk", "Input 3DTK scan (scanNNN.3d); this or --rawlog", false, "",
	    "F.3d", cmd);
	TCLAP::ValueArg<std::string> argOut(
	    "", "out", "Output directory (created if needed); required", false, "",
	    "DIR", cmd);
	TCLAP::ValueArg<std::string>& argGt =
	    cli.addGtDir("scores labels and objects");
	semnav::PerceptionRun::Settings s;
	semnav::IniSections sections;
	sections.add(s.perception, "", semnav::PerceptionPipeline::sections())
	    .add(s.assembler, "SweepAssembler")
	    .add(s.threeDtk, "ThreeDtkReader");
	TCLAP::ValueArg<std::string>& argConfig =
	    cli.addConfig(sections, "INI file (see config/perception.ini)");
	semnav::CascadeArgs cascades(cli);
	TCLAP::SwitchArg& argJson = cli.addJson();
	if (const auto code = cli.parse(argc, argv)) return *code;
	s.rawlog = argRawlog.getValue();
	s.scan3dtk = argTdtk.getValue();
	s.out = argOut.getValue();
	s.gtDir = argGt.getValue();
	if (s.rawlog.empty() == s.scan3dtk.empty())
		return cli.usageError("give exactly one of --rawlog and --3dtk");
	if (s.out.empty()) return cli.usageError("missing --out");
	return cli.run(
	    [&]
	    {
		    sections.loadIfGiven(argConfig.getValue());
		    if (const auto file = cascades.file())
			    s.cascades =
			        semnav::CascadeDetector::TOptions::fromIniFile(*file);
		    semnav::PerceptionRun run(s);
		    const std::string input = s.rawlog.empty() ? s.scan3dtk : s.rawlog;
		    semnav::ProgressBar bar(
		        run.expectedSweeps(),
		        "perceiving " + std::filesystem::path(input).stem().string());
		    run.run([&](std::size_t done) { bar.update(done); });
		    bar.finish();
		    if (argJson.getValue())
			    printJson(run);
		    else
			    printText(run, s.out);
		    return 0;
	    });
}
