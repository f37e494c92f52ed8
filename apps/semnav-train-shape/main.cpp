/* semnav: semantic navigation from tilting-laser sweeps */
// semnav-train-shape: trains one class's 3D shape model (ShapeVerifier) on
// the cascade's candidates in simulated datasets.
#include <semnav/common/CommandLine.h>
#include <semnav/common/DatasetListArg.h>
#include <semnav/common/ProgressBar.h>
#include <semnav/detection/ShapeVerifier.h>
#include <semnav/training/CascadeConfigArg.h>
#include <semnav/training/CascadeTraining.h>
#include <semnav/training/ShapeTraining.h>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

int main(int argc, char** argv)
{
	semnav::CommandLine cli(
	    "semnav-train-shape",
	    "Trains the 3D shape model of one object class: runs perception and "
	    "the cascade (looser than detection) on simulated datasets, "
	    "describes every candidate that passes the size check (ObjectShape) "
	    "and labels it by the ground truth, then fits a random forest "
	    "(cv::ml::RTrees) that the detector's shape check uses.");
	auto& cmd = cli.cmd();
	TCLAP::ValueArg<std::string> argLabel(
	    "", "label", "Object class: washbasin, wastebasket or stairs; required",
	    false, "", "L", cmd);
	semnav::DatasetListArg argDatasets(
	    cmd, "Dataset directories (semnav-sim output); required");
	const semnav::CascadeConfigArg argConfig(cli, true);
	TCLAP::ValueArg<std::string> argOut(
	    "", "out", "Output shape model (OpenCV XML); required", false, "",
	    "L-shape.xml.gz", cmd);
	TCLAP::ValueArg<int> argNeighbors(
	    "", "min-neighbors",
	    "The cascade's min_neighbors while collecting (-1: the config's); "
	    "default 0",
	    false, 0, "N", cmd);
	TCLAP::ValueArg<int> argStages(
	    "", "max-stages",
	    "Only the cascade's first N stages while collecting (-1: the "
	    "config's); default 10",
	    false, 10, "N", cmd);
	TCLAP::ValueArg<double> argBalance(
	    "", "max-objects-per-other",
	    "At most this many object samples per other sample (0: all); "
	    "default 2",
	    false, 2, "R", cmd);
	TCLAP::ValueArg<double> argPurity(
	    "", "min-purity",
	    "An object sample's measured points are at least this share of that "
	    "object's (fewer: left out as ambiguous; 0: no check); default 0",
	    false, 0, "P", cmd);
	TCLAP::ValueArg<double> argObjectIou(
	    "", "object-iou",
	    "A sample is an object when its measured box has at least this IoU "
	    "with one (in (0.1, 1]; boxes between 0.1 and it are left out as "
	    "ambiguous); default 0.3",
	    false, 0.3, "IOU", cmd);
	TCLAP::ValueArg<int> argMaxSamples(
	    "", "max-samples",
	    "At most this many samples (a random subset, 0: all); default 30000",
	    false, 30000, "N", cmd);
	TCLAP::ValueArg<int> argTrees(
	    "", "trees", "Trees in the forest; default 100", false, 100, "N", cmd);
	TCLAP::ValueArg<int> argDepth(
	    "", "max-depth", "Depth of the trees; default 10", false, 10, "N", cmd);
	TCLAP::ValueArg<int> argSeed(
	    "", "seed", "Random seed; default 1", false, 1, "N", cmd);
	TCLAP::SwitchArg argWithoutGrids(
	    "", "without-grids",
	    "Train on the scalar shape features only, not the object-frame "
	    "grids",
	    cmd, false);
	TCLAP::SwitchArg argWithSteps(
	    "", "with-steps",
	    "Train on the steps along the sweep's columns too (a flight's "
	    "risers)",
	    cmd, false);
	TCLAP::SwitchArg argWithoutWindow(
	    "", "without-segment-window",
	    "Measure segment candidates without segment_range_window, as the "
	    "shipped forests learnt them",
	    cmd, false);
	TCLAP::ValueArg<double> argSlack(
	    "", "range-scale-slack",
	    "The range gate's range_scale_slack while collecting (in [1, 10]; "
	    "0: the config's); default 0",
	    false, 0, "S", cmd);
	TCLAP::SwitchArg& argJson = cli.addJson();
	if (const auto code = cli.parse(argc, argv)) return *code;
	const std::vector<std::string> datasets = argDatasets.values();
	if (datasets.empty()) return cli.usageError("missing --datasets");
	for (auto* a : {&argLabel, &argOut})
		if (a->getValue().empty())
			return cli.usageError("missing --" + a->getName());
	if (!(argPurity.getValue() >= 0 && argPurity.getValue() <= 1))
		return cli.usageError("--min-purity must be in [0, 1]");
	if (!(argObjectIou.getValue() > 0.1 && argObjectIou.getValue() <= 1))
		return cli.usageError("--object-iou must be in (0.1, 1]");
	if (argSlack.getValue() != 0 &&
	    !(argSlack.getValue() >= 1 && argSlack.getValue() <= 10))
		return cli.usageError("--range-scale-slack must be 0 or in [1, 10]");

	return cli.run(
	    [&]
	    {
		    const semnav::Label label =
		        semnav::labelFromName(argLabel.getValue());
		    auto detector = semnav::CascadeDetector::TOptions::fromIniFile(
		        argConfig.path());
		    if (argWithoutWindow.getValue())
			    detector.segmentRangeWindow = false;
		    if (argSlack.getValue() != 0)
			    detector.rangeScaleSlack = argSlack.getValue();
		    semnav::ShapeTraining::Params params;
		    params.minNeighbors = argNeighbors.getValue();
		    params.maxStages = argStages.getValue();
		    params.maxObjectsPerOther = argBalance.getValue();
		    params.seed = static_cast<uint64_t>(argSeed.getValue());
		    params.grids = !argWithoutGrids.getValue();
		    params.steps = argWithSteps.getValue();
		    params.minPurity = argPurity.getValue();
		    params.objectIou = argObjectIou.getValue();
		    params.maxSamples =
		        static_cast<std::size_t>(std::max(0, argMaxSamples.getValue()));
		    std::unique_ptr<semnav::ProgressBar> bar;
		    std::string current;
		    const auto samples = semnav::ShapeTraining::collect(
		        datasets, detector, label, params,
		        [&](const std::string& dir, std::size_t done, std::size_t all)
		        {
			        if (dir != current)
			        {
				        bar = std::make_unique<semnav::ProgressBar>(
				            all, "candidates in " + dir);
				        current = dir;
			        }
			        bar->update(done);
		        });
		    bar.reset();
		    semnav::ShapeVerifier::TrainParams tp;
		    tp.trees = argTrees.getValue();
		    tp.maxDepth = argDepth.getValue();
		    tp.seed = static_cast<uint64_t>(argSeed.getValue());
		    const auto forest = semnav::ShapeVerifier::train(
		        samples.features, samples.isObject, tp);
		    forest.save(argOut.getValue());
		    nlohmann::json j{{"label", argLabel.getValue()},
		                     {"sweeps", samples.sweeps},
		                     {"objects", samples.objects},
		                     {"others", samples.others},
		                     {"ambiguous", samples.ambiguous},
		                     {"impure", samples.impure},
		                     {"out", argOut.getValue()},
		                     {"features", samples.features.cols}};
		    if (argJson.getValue())
			    std::cout << j.dump() << std::endl;
		    else
			    std::printf(
			        "%s: %zu sweeps, %zu object and %zu other samples "
			        "(%zu ambiguous candidates left out, %zu of them on "
			        "another object), %d features -> %s\n",
			        argLabel.getValue().c_str(), samples.sweeps,
			        samples.objects, samples.others, samples.ambiguous,
			        samples.impure, samples.features.cols,
			        argOut.getValue().c_str());
		    return 0;
	    });
}
