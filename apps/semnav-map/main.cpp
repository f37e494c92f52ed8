/* semnav: semantic navigation from tilting-laser sweeps */
// semnav-map: rawlog -> semantic map directory (docs/design.md, "Apps").
#include <mrpt/config/CConfigFile.h>
#include <semnav/common/CommandLine.h>
#include <semnav/common/ConfigChecks.h>
#include <semnav/common/Error.h>
#include <semnav/common/ProgressBar.h>
#include <semnav/detection/SweepPerception.h>
#include <semnav/localization/MappingLocalizer.h>
#include <semnav/localization/TrajectoryError.h>
#include <semnav/map/MapIO.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/perception/GroundTruthScorer.h>
#include <semnav/perception/PerceptionPipeline.h>
#include <semnav/scan/GroundTruthLog.h>
#include <semnav/scan/RawlogSweepReader.h>
#include <semnav/scan/ThreeDtkReader.h>

#include <algorithm>
#include <chrono>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>

int main(int argc, char** argv)
{
	semnav::CommandLine cli(
	    "semnav-map",
	    "Builds a semantic map from a rawlog of tilting-laser sweeps: "
	    "perception on every sweep, insertion at the robot pose, then the map "
	    "directory (map.yaml, occupancy.png, labels.png, cost.png, map.png, "
	    "octomap.bt).");
	auto& cmd = cli.cmd();
	TCLAP::ValueArg<std::string> argRawlog(
	    "", "rawlog", "Input rawlog (or --3dtk)", false, "", "R", cmd);
	TCLAP::MultiArg<std::string> arg3dtk(
	    "", "3dtk",
	    "Real 3DTK scans (scanNNN.3d, poses from scanNNN.pose) instead of a "
	    "rawlog; repeat for several",
	    false, "F.3d", cmd);
	TCLAP::ValueArg<std::string> argOut(
	    "", "out", "Map directory to write; required", false, "", "MAPDIR",
	    cmd);
	TCLAP::ValueArg<std::string> argConfig(
	    "", "config", "INI file (see config/map.ini)", false, "", "C.ini", cmd);
	TCLAP::ValueArg<std::string> argCascades(
	    "", "cascades",
	    "Detect washbasins, wastebaskets and stairs with the Haar cascades "
	    "of this detector INI file (config/cascade.ini); without it the map "
	    "has doors but no such objects",
	    false, "", "C.ini", cmd);
	TCLAP::ValueArg<std::string> argPoses(
	    "", "poses",
	    "Robot poses: odometry (default), gt (needs --gt-dir or the gt file "
	    "next to the rawlog) or pf",
	    false, "odometry", "odometry|gt|pf", cmd);
	TCLAP::ValueArg<std::string> argLocConfig(
	    "", "loc-config",
	    "Localization INI file for --poses pf (see config/localization.ini)",
	    false, "", "C.ini", cmd);
	TCLAP::ValueArg<std::string> argGt(
	    "", "gt-dir",
	    "Directory written by semnav-sim (<name>.gt.txt, <name>.labels/): "
	    "adds per-class scores to the summary",
	    false, "", "DIR", cmd);
	TCLAP::SwitchArg argJson(
	    "", "json", "Print a JSON summary on stdout", cmd, false);
	if (const auto code = cli.parse(argc, argv)) return *code;
	if (argOut.getValue().empty()) return cli.usageError("missing --out");
	if (argRawlog.getValue().empty() == arg3dtk.getValue().empty())
		return cli.usageError("give either --rawlog or --3dtk");
	const std::string poses = argPoses.getValue();
	if (poses != "odometry" && poses != "gt" && poses != "pf")
		return cli.usageError(
		    "--poses must be odometry, gt or pf, got '" + poses + "'");

	return cli.run(
	    [&]
	    {
		    namespace fs = std::filesystem;
		    semnav::SemanticMap::TOptions mapOpts;
		    semnav::PerceptionPipeline::TOptions percOpts;
		    semnav::SweepAssembler::TOptions asmOpts;
		    if (!argConfig.getValue().empty())
		    {
			    std::vector<std::string> sections = {
			        "SemanticMap", "TravelCost", "SweepAssembler"};
			    for (const auto& s : semnav::PerceptionPipeline::sections())
				    sections.push_back(s);
			    const auto cfg =
			        semnav::openIniFile(argConfig.getValue(), sections);
			    mapOpts.loadFromConfigFile(*cfg, "SemanticMap");
			    mapOpts.cost.loadFromConfigFile(*cfg, "TravelCost");
			    asmOpts.loadFromConfigFile(*cfg, "SweepAssembler");
			    percOpts.loadFromConfigFile(*cfg, "");
		    }
		    const std::string rawlog = argRawlog.getValue();
		    std::optional<semnav::GroundTruthLog> gt;
		    if (!argGt.getValue().empty())
			    gt =
			        semnav::GroundTruthLog::forRawlog(argGt.getValue(), rawlog);
		    else if (poses == "gt" && !rawlog.empty())
			    gt = semnav::GroundTruthLog::forRawlog(
			        fs::path(rawlog).parent_path().string(), rawlog);

		    // Sweeps from the rawlog, or from the 3DTK files one by one.
		    std::unique_ptr<semnav::RawlogSweepReader> reader;
		    if (!rawlog.empty())
			    reader = std::make_unique<semnav::RawlogSweepReader>(
			        rawlog, asmOpts);
		    const auto& scans3dtk = arg3dtk.getValue();
		    std::size_t next3dtk = 0;
		    auto nextSweep = [&](semnav::Sweep& s)
		    {
			    if (reader) return reader->next(s);
			    if (next3dtk == scans3dtk.size()) return false;
			    s = semnav::ThreeDtkReader().read(scans3dtk[next3dtk]);
			    s.setIndex(next3dtk++);
			    return true;
		    };
		    std::optional<semnav::CascadeDetector::TOptions> cascadeOpts;
		    if (!argCascades.getValue().empty())
			    cascadeOpts = semnav::CascadeDetector::TOptions::fromIniFile(
			        argCascades.getValue());
		    semnav::SweepPerception perception(percOpts, cascadeOpts);
		    semnav::SemanticMap map(mapOpts);
		    // --poses pf: each sweep localized against the map so far.
		    std::unique_ptr<semnav::MappingLocalizer> localizer;
		    if (poses == "pf")
		    {
			    semnav::MappingLocalizer::TOptions locOpts;
			    if (!argLocConfig.getValue().empty())
				    locOpts.loadFromConfigFile(
				        *semnav::openIniFile(
				            argLocConfig.getValue(),
				            semnav::MappingLocalizer::TOptions::sections()),
				        "");
			    localizer = std::make_unique<semnav::MappingLocalizer>(locOpts);
		    }
		    semnav::TrajectoryError poseError, odometryError;
		    std::vector<double> locMs;
		    semnav::GroundTruthScorer scorer;
		    semnav::ProgressBar bar(gt ? gt->size() : 0, "mapping");
		    std::vector<double> ms;
		    std::string readError;
		    semnav::Sweep sweep;
		    for (;;)
		    {
			    try
			    {
				    if (!nextSweep(sweep)) break;
			    }
			    catch (const semnav::RawlogError& e)
			    {
				    readError = e.what();  // keep the map of the good sweeps
				    break;
			    }
			    const auto t0 = std::chrono::steady_clock::now();
			    const semnav::LabeledSweep ls = perception.process(sweep);
			    mrpt::poses::CPose2D pose = sweep.odometry();
			    if (poses == "gt")
			    {
				    if (!gt)
					    throw semnav::Error(
					        "--poses gt needs a rawlog from semnav-sim (or "
					        "--gt-dir)");
				    pose = gt->pose(sweep.index());
			    }
			    if (localizer)
			    {
				    pose = localizer->process(sweep, ls, map);
				    if (map.sweepsInserted() > 1)
					    locMs.push_back(localizer->lastUpdate().ms);
			    }
			    else
				    map.insert(sweep, ls, pose);
			    if (gt && !argGt.getValue().empty())
			    {
				    const auto& truth = gt->pose(sweep.index());
				    poseError.add(pose, truth);
				    odometryError.add(sweep.odometry(), truth);
			    }
			    ms.push_back(std::chrono::duration<double, std::milli>(
			                     std::chrono::steady_clock::now() - t0)
			                     .count());
			    if (gt && !argGt.getValue().empty())
				    scorer.add(
				        ls.labels,
				        semnav::GroundTruthScorer::readLabelImage(
				            gt->labelImagePath(sweep.index())),
				        ls.validMask);
			    bar.update(ms.size());
		    }
		    bar.finish();
		    semnav::MapIO::save(map, argOut.getValue());

		    double median = 0;
		    if (!ms.empty())
		    {
			    std::nth_element(
			        ms.begin(), ms.begin() + ms.size() / 2, ms.end());
			    median = ms[ms.size() / 2];
		    }
		    nlohmann::json j;
		    j["sweeps"] = map.sweepsInserted();
		    j["objects"] = nlohmann::json::array();
		    for (const auto& o : map.instances())
			    j["objects"].push_back(
			        {{"id", o.id},
			         {"label", semnav::labelName(o.label)},
			         {"x", o.centroid.x},
			         {"y", o.centroid.y},
			         {"z", o.centroid.z},
			         {"observations", o.observations}});
		    j["classes"] = nlohmann::json::object();
		    for (semnav::Label l : scorer.labelsSeen())
		    {
			    const auto s = scorer.score(l);
			    j["classes"][semnav::labelName(l)] = {
			        {"precision", s.precision},
			        {"recall", s.recall},
			        {"f1", s.f1},
			        {"pixels", s.groundTruthPixels}};
		    }
		    j["ms_per_sweep_median"] = median;
		    if (poseError.size() > 0)
		    {
			    double locMedian = 0;
			    if (!locMs.empty())
			    {
				    std::nth_element(
				        locMs.begin(), locMs.begin() + locMs.size() / 2,
				        locMs.end());
				    locMedian = locMs[locMs.size() / 2];
			    }
			    j["localization"] = {
			        {"poses", poses},
			        {"rmse_xy_m", poseError.rmseXY()},
			        {"final_yaw_err_deg", mrpt::RAD2DEG(poseError.finalYaw())},
			        {"max_yaw_err_deg", mrpt::RAD2DEG(poseError.maxYaw())},
			        {"odometry_final_yaw_err_deg",
			         mrpt::RAD2DEG(odometryError.finalYaw())},
			        {"odometry_rmse_xy_m", odometryError.rmseXY()},
			        {"ms_per_update_median", locMedian}};
		    }
		    j["map"] = argOut.getValue();
		    if (argJson.getValue())
			    std::cout << j.dump() << std::endl;
		    else
		    {
			    std::cout << "semnav-map: " << map.sweepsInserted()
			              << " sweeps (" << poses << " poses), "
			              << map.instances().size() << " objects, " << median
			              << " ms/sweep (median)\n";
			    for (const auto& o : map.instances())
				    std::cout << "  #" << o.id << " "
				              << semnav::labelName(o.label) << " at ("
				              << o.centroid.x << ", " << o.centroid.y
				              << "), seen " << o.observations << "x\n";
			    if (j.contains("localization"))
			    {
				    const auto& l = j["localization"];
				    std::cout << "  localization (" << poses << "): RMSE xy "
				              << l["rmse_xy_m"].get<double>()
				              << " m, final yaw error "
				              << l["final_yaw_err_deg"].get<double>()
				              << " deg (odometry: "
				              << l["odometry_rmse_xy_m"].get<double>() << " m, "
				              << l["odometry_final_yaw_err_deg"].get<double>()
				              << " deg)\n";
			    }
			    std::cout << "  map: " << argOut.getValue()
			              << "/map.yaml, rendering " << argOut.getValue()
			              << "/map.png\n";
		    }
		    if (!readError.empty())
			    throw semnav::RawlogError(
			        readError + " (map of the sweeps before it written)");
		    return 0;
	    });
}
