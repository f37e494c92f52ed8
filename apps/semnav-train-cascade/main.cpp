/* semnav: semantic navigation from tilting-laser sweeps */
// semnav-train-cascade: trains one class's Haar cascade from simulated
// datasets and writes it in OpenCV's XML format (docs/design.md, "Apps").
#include <semnav/cascade/CascadeEvaluator.h>
#include <semnav/cascade/CascadeXml.h>
#include <semnav/common/AtomicFile.h>
#include <semnav/common/CommandLine.h>
#include <semnav/common/DatasetListArg.h>
#include <semnav/common/Error.h>
#include <semnav/common/ProgressBar.h>
#include <semnav/training/CascadeConfigArg.h>
#include <semnav/training/CascadeTraining.h>

#include <cstdint>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace
{
/** How many of `positives` the cascade XML `xml` accepts. */
void printPositiveScore(
    const std::vector<cv::Mat>& positives, const std::string& xml, bool json)
{
	semnav::CascadeEvaluator ev(semnav::CascadeXml::readFile(xml));
	std::size_t accepted = 0, lowContrast = 0;
	for (const auto& p : positives)
	{
		ev.setImage(p);
		const auto r = ev.evaluate({0, 0});
		accepted += ev.accepted(r);
		lowContrast += r.skipped();
	}
	const std::size_t n = positives.size();
	const double f = n == 0 ? 0.0 : double(accepted) / double(n);
	if (json)
		std::cout
		    << nlohmann::
		           json{{"positives", n}, {"accepted", accepted}, {"low_contrast", lowContrast}, {"accepted_fraction", f}}
		               .dump()
		    << std::endl;
	else
		std::printf(
		    "%s: %zu of %zu positives accepted (%.3f), %zu of low contrast "
		    "(never evaluated)\n",
		    xml.c_str(), accepted, n, f, lowContrast);
}

/** The first 400 positive samples, 20 by 20, enlarged 2x, as a PNG. */
void writeMosaic(
    const std::vector<cv::Mat>& samples, cv::Size window,
    const std::string& path)
{
	const int n = 20, w = window.width, h = window.height;
	cv::Mat mosaic(n * (h + 1), n * (w + 1), CV_8UC1, cv::Scalar(0));
	for (int i = 0; i < n * n && i < int(samples.size()); i++)
		samples[i].copyTo(
		    mosaic(cv::Rect((i % n) * (w + 1), (i / n) * (h + 1), w, h)));
	cv::resize(mosaic, mosaic, cv::Size(), 2, 2, cv::INTER_NEAREST);
	semnav::writeAtomically(
	    path,
	    [&](const std::string& tmp)
	    {
		    if (!cv::imwrite(tmp + ".png", mosaic) ||
		        std::rename((tmp + ".png").c_str(), tmp.c_str()) != 0)
			    throw semnav::IoError("cannot write " + path);
	    });
}

nlohmann::json trainingJson(
    const semnav::CascadeTraining::Result& res, const std::string& label,
    const std::string& out, uint64_t seed)
{
	nlohmann::json j;
	j["label"] = label;
	j["out"] = out;
	j["seed"] = seed;
	j["sweeps"] = res.sweeps;
	j["object_views"] = res.views;
	j["positives"] = res.positives;
	j["positives_low_contrast"] = res.report.positivesLowContrast;
	j["negative_images"] = res.negativeImages;
	j["feature_pool"] = res.report.featurePool;
	j["stages"] = res.cascade.stages.size();
	j["stumps"] = res.cascade.stumpCount();
	j["features"] = res.cascade.features.size();
	j["tilted_features"] = res.cascade.hasTiltedFeatures();
	j["final_acceptance_ratio"] = res.report.finalAcceptanceRatio;
	j["stop_reason"] = res.report.stopReason;
	j["seconds"] = res.seconds();
	j["seconds_load"] = res.secondsLoad;
	j["seconds_samples"] = res.secondsSamples;
	j["seconds_training"] = res.secondsTraining;
	nlohmann::json stages = nlohmann::json::array();
	for (const auto& s : res.report.stages)
		stages.push_back(
		    {{"positives", s.positives},
		     {"negatives", s.negatives},
		     {"stumps", s.weakCount},
		     {"hit_rate", s.hitRate},
		     {"calibration_positives", s.calibrationPositives},
		     {"calibration_hit_rate", s.calibrationHitRate},
		     {"false_alarm", s.falseAlarm},
		     {"acceptance_ratio", s.acceptanceRatio},
		     {"seconds", s.seconds},
		     {"seconds_negatives", s.secondsNegatives},
		     {"seconds_binning", s.secondsBinning},
		     {"seconds_boosting", s.secondsBoosting}});
	j["stage_details"] = stages;
	return j;
}

void printTraining(
    const semnav::CascadeTraining::Result& res, const std::string& label,
    const std::string& out)
{
	std::cout << label << ": " << res.cascade.stages.size() << " stages, "
	          << res.cascade.stumpCount() << " stumps ("
	          << res.report.stopReason << "), from " << res.positives
	          << " positives (" << res.views << " object views in "
	          << res.sweeps << " sweeps); negative acceptance "
	          << res.report.finalAcceptanceRatio << "\n"
	          << "  training time: " << res.seconds() << " s (load "
	          << res.secondsLoad << " s, samples " << res.secondsSamples
	          << " s, boosting " << res.secondsTraining << " s)\n"
	          << "  written: " << out << "\n";
}
}  // namespace

int main(int argc, char** argv)
{
	semnav::CommandLine cli(
	    "semnav-train-cascade",
	    "Trains a Haar cascade (Viola-Jones with Lienhart's rotated features, "
	    "Gentle AdaBoost) for one object class on the normal images of "
	    "simulated sweeps, and writes it as OpenCV cascade XML.");
	auto& cmd = cli.cmd();
	TCLAP::ValueArg<std::string> argLabel(
	    "", "label", "Object class: washbasin, wastebasket or stairs; required",
	    false, "", "L", cmd);
	semnav::DatasetListArg argDatasets(
	    cmd,
	    "Dataset directories written by semnav-sim (rawlog + labels); the "
	    "first one follows --datasets, more may follow it; required");
	TCLAP::ValueArg<std::string> argOut(
	    "", "out", "Output cascade XML; required", false, "", "L.xml", cmd);
	TCLAP::ValueArg<std::string> argSeed(
	    "", "seed", "Random seed (samples, negatives); default 1", false, "1",
	    "N", cmd);
	const semnav::CascadeConfigArg argConfig(cli, false);
	TCLAP::ValueArg<std::string> argSamples(
	    "", "samples",
	    "Also write a mosaic of the first 400 positive samples to this PNG",
	    false, "", "P.png", cmd);
	TCLAP::ValueArg<std::string> argScore(
	    "", "score-positives",
	    "Do not train: make the positives training would make (same "
	    "datasets, configuration; --seed) and print how many of them this "
	    "cascade XML accepts (a cascade accepts most of the positives it was "
	    "trained on; another seed gives new samples of the same objects)",
	    false, "", "C.xml", cmd);
	TCLAP::SwitchArg& argJson = cli.addJson();
	if (const auto code = cli.parse(argc, argv)) return *code;
	const std::vector<std::string> datasets = argDatasets.values();
	if (datasets.empty()) return cli.usageError("missing --datasets");
	for (auto* a : {&argLabel})
		if (a->getValue().empty())
			return cli.usageError("missing --" + a->getName());
	if (argScore.getValue().empty() && argOut.getValue().empty())
		return cli.usageError("missing --out");
	const auto seed = semnav::CommandLine::parseUnsigned(argSeed.getValue());
	if (!seed)
		return cli.usageError(
		    "--seed must be a non-negative integer, got '" +
		    argSeed.getValue() + "'");

	return cli.run(
	    [&]
	    {
		    const semnav::Label label =
		        semnav::labelFromName(argLabel.getValue());
		    semnav::CascadeTraining::TOptions opts;
		    if (!argConfig.path().empty())
			    opts = semnav::CascadeTraining::TOptions::fromIniFile(
			        argConfig.path());
		    const semnav::CascadeTraining training(opts);
		    if (!argScore.getValue().empty())
		    {
			    printPositiveScore(
			        training.positives(label, datasets, *seed),
			        argScore.getValue(), argJson.getValue());
			    return 0;
		    }
		    semnav::ProgressBar bar(
		        2 + static_cast<std::size_t>(opts.trainerFor(label).numStages),
		        "training " + argLabel.getValue());
		    const auto res = training.run(
		        label, datasets, *seed,
		        [&](std::size_t done, std::size_t, const std::string&)
		        { bar.update(done); });
		    bar.finish();

		    // The XML says how to make it again (no times: same command,
		    // same bytes).
		    std::ostringstream how;
		    how << "semnav " << argLabel.getValue()
		        << " cascade, made by: semnav-train-cascade --label "
		        << argLabel.getValue() << " --datasets";
		    for (const auto& d : datasets) how << " " << d;
		    how << " --out " << argOut.getValue() << " --seed " << *seed;
		    if (!argConfig.path().empty())
			    how << " --config " << argConfig.path();
		    semnav::HaarCascade cascade = res.cascade;
		    cascade.note = how.str();
		    semnav::CascadeXml::writeFile(argOut.getValue(), cascade);

		    if (!argSamples.getValue().empty())
		    {
			    writeMosaic(
			        res.positiveSamples, res.cascade.windowSize,
			        argSamples.getValue());
		    }
		    if (argJson.getValue())
			    std::cout << trainingJson(
			                     res, argLabel.getValue(), argOut.getValue(),
			                     *seed)
			                     .dump()
			              << std::endl;
		    else
			    printTraining(res, argLabel.getValue(), argOut.getValue());
		    return 0;
	    });
}
