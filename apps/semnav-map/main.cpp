/* semnav: semantic navigation from tilting-laser sweeps */
// semnav-map: rawlog -> semantic map directory (docs/design.md, "Apps").
#include <semnav/common/CascadeArgs.h>
#include <semnav/common/CommandLine.h>
#include <semnav/common/Error.h>
#include <semnav/common/IniSections.h>
#include <semnav/common/Percentile.h>
#include <semnav/common/ProgressBar.h>
#include <semnav/map/MapIO.h>
#include <semnav/mapping/MapBuilder.h>
#include <semnav/training/ScoreJson.h>

#include <iostream>
#include <nlohmann/json.hpp>

namespace
{
/** Per update: the estimate's covariance, its largest xy std dev and that
 * direction, and the directions that followed the odometry. */
nlohmann::json covarianceJson(const semnav::MapBuilder& b)
{
	nlohmann::json j = nlohmann::json::array();
	for (const auto& u : b.localizationUpdates())
		j.push_back(
		    {{"x", u.pose.x()},
		     {"y", u.pose.y()},
		     {"yaw_deg", mrpt::RAD2DEG(u.pose.phi())},
		     {"largest_std_m", u.largestStd},
		     {"largest_std_direction_deg",
		      mrpt::RAD2DEG(u.largestStdDirection)},
		     {"std_yaw_deg", mrpt::RAD2DEG(u.stdYaw)},
		     {"directions_following_odometry", u.unconstrained},
		     {"heading_corrected", u.headingCorrected},
		     {"heading_from_borders", u.headingFromBorders}});
	return j;
}

nlohmann::json summary(
    const semnav::MapBuilder& b, const std::string& poses,
    const std::string& out)
{
	nlohmann::json j;
	j["sweeps"] = b.map().sweepsInserted();
	j["sweeps_skipped_incomplete"] = b.sweepsSkippedIncomplete();
	j["sweeps_dropped_moving"] = b.sweepsDroppedMoving();
	j["sweeps_failed"] = b.sweepsFailed();
	j["objects"] = nlohmann::json::array();
	j["not_reported"] = nlohmann::json::array();
	for (const auto& o : b.map().allInstances())
	{
		const std::string reason = b.map().unreportedReason(o);
		// Copies: json's initializer lists bind references, and MRPT packs
		// TPoint3D (misaligned doubles).
		const double x = o.centroid.x, y = o.centroid.y, z = o.centroid.z;
		const mrpt::math::TPoint3D e = o.extent();
		const double ex = e.x, ey = e.y, ez = e.z;
		nlohmann::json object = {
		    {"id", o.id},
		    {"label", semnav::labelName(o.label)},
		    {"x", x},
		    {"y", y},
		    {"z", z},
		    {"extent", {ex, ey, ez}},
		    {"observations", o.observations},
		    {"views", o.views}};
		auto& sizes = object["sighting_sizes_m"] = nlohmann::json::array();
		for (const auto& size : o.sightingSizes)
		{
			const double w = size.x, h = size.z;
			sizes.push_back({w, h});
		}
		if (!reason.empty()) object["rule"] = reason;
		j[reason.empty() ? "objects" : "not_reported"].push_back(object);
	}
	j["classes"] = semnav::labelScoresJson(b.labelScores());
	j["ms_per_sweep_median"] = semnav::median(b.msPerSweep());
	if (b.poseError().size() > 0)
		j["localization"] = {
		    {"poses", poses},
		    {"rmse_xy_m", b.poseError().rmseXY()},
		    {"final_yaw_err_deg", mrpt::RAD2DEG(b.poseError().finalYaw())},
		    {"max_yaw_err_deg", mrpt::RAD2DEG(b.poseError().maxYaw())},
		    {"odometry_final_yaw_err_deg",
		     mrpt::RAD2DEG(b.odometryError().finalYaw())},
		    {"odometry_rmse_xy_m", b.odometryError().rmseXY()},
		    {"ms_per_update_median", semnav::median(b.msPerLocalization())}};
	if (!b.localizationUpdates().empty())
	{
		const auto& last = b.localizationUpdates().back();
		double maxStd = 0;
		for (const auto& u : b.localizationUpdates())
			maxStd = std::max(maxStd, u.largestStd);
		auto& l = j["localization"];
		l["final_largest_std_m"] = last.largestStd;
		l["final_largest_std_direction_deg"] =
		    mrpt::RAD2DEG(last.largestStdDirection);
		l["max_largest_std_m"] = maxStd;
		l["updates"] = covarianceJson(b);
	}
	j["map"] = out;
	return j;
}

void printSummary(const nlohmann::json& j, const std::string& poses)
{
	std::cout << "semnav-map: " << j["sweeps"] << " sweeps (" << poses
	          << " poses), " << j["objects"].size() << " objects, "
	          << j["ms_per_sweep_median"].get<double>()
	          << " ms/sweep (median)\n";
	if (j["sweeps_skipped_incomplete"] > 0 || j["sweeps_dropped_moving"] > 0)
		std::cout << "  not mapped: " << j["sweeps_skipped_incomplete"]
		          << " incomplete sweeps, " << j["sweeps_dropped_moving"]
		          << " pieces of sweeps taken while driving\n";
	if (j["sweeps_failed"] > 0)
		std::cout << "  skipped: " << j["sweeps_failed"]
		          << " sweeps whose perception failed (see stderr)\n";
	for (const auto& o : j["objects"])
		std::cout << "  #" << o["id"] << " " << o["label"].get<std::string>()
		          << " at (" << o["x"].get<double>() << ", "
		          << o["y"].get<double>() << "), seen " << o["observations"]
		          << "x\n";
	if (!j["not_reported"].empty())
		std::cout << "  not reported: " << j["not_reported"].size()
		          << (j["not_reported"].size() == 1 ? " candidate"
		                                            : " candidates")
		          << " held back by the [SemanticMap] rules (--json names "
		             "each one's rule)\n";
	if (j.contains("localization") && j["localization"].contains("rmse_xy_m"))
	{
		const auto& l = j["localization"];
		std::cout << "  localization (" << poses << "): RMSE xy "
		          << l["rmse_xy_m"].get<double>() << " m, final yaw error "
		          << l["final_yaw_err_deg"].get<double>()
		          << " deg (odometry: " << l["odometry_rmse_xy_m"].get<double>()
		          << " m, " << l["odometry_final_yaw_err_deg"].get<double>()
		          << " deg)\n";
	}
	if (j.contains("localization") &&
	    j["localization"].contains("final_largest_std_m"))
	{
		const auto& l = j["localization"];
		std::cout << "  covariance: largest std "
		          << l["final_largest_std_m"].get<double>() << " m along "
		          << l["final_largest_std_direction_deg"].get<double>()
		          << " deg at the end (max "
		          << l["max_largest_std_m"].get<double>() << " m)\n";
	}
	const std::string out = j["map"];
	std::cout << "  map: " << out << "/map.yaml, rendering " << out
	          << "/map.png\n";
}

/** How the sweeps read add up to the map written, e.g. "the map of 4 of
 * them written, 1 incomplete left out". */
std::string mappedOfRead(const semnav::MapBuilder& b)
{
	std::string s = "the map of " + std::to_string(b.map().sweepsInserted()) +
	                " of them written";
	if (b.sweepsSkippedIncomplete() > 0)
		s += ", " + std::to_string(b.sweepsSkippedIncomplete()) +
		     " incomplete left out";
	if (b.sweepsFailed() > 0)
		s += ", " + std::to_string(b.sweepsFailed()) + " failed";
	return s;
}
}  // namespace

int main(int argc, char** argv)
{
	semnav::CommandLine cli(
	    "semnav-map",
	    "Builds a semantic map from a rawlog of tilting-laser sweeps: "
	    "perception on every sweep (rules, Haar cascades and 3D checks), "
	    "insertion at the robot pose, then the map directory (map.yaml, "
	    "occupancy.png, labels.png, cost.png, map.png, octomap.bt).");
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
	semnav::MapBuilder::Settings s;
	semnav::IniSections sections;
	sections.add(s.map, "SemanticMap")
	    .add(s.map.cost, "TravelCost")
	    .add(s.assembler, "SweepAssembler")
	    .add(s.perception, "", semnav::PerceptionPipeline::sections())
	    .add(
	        s.localization, "", semnav::MappingLocalizer::TOptions::sections());
	TCLAP::ValueArg<std::string>& argConfig =
	    cli.addConfig(sections, "INI file (see config/map.ini)");
	semnav::CascadeArgs cascades(cli);
	TCLAP::ValueArg<std::string> argPoses(
	    "", "poses",
	    "Robot poses: odometry, gt (needs --gt-dir or the gt file next to "
	    "the rawlog) or pf (default: each sweep localized against the map so "
	    "far)",
	    false, "pf", "odometry|gt|pf", cmd);
	TCLAP::ValueArg<std::string> argLocConfig(
	    "", "loc-config",
	    "Localization INI file for --poses pf (see config/localization.ini); "
	    "read after --config",
	    false, "", "C.ini", cmd);
	TCLAP::ValueArg<std::string>& argGt =
	    cli.addGtDir("adds per-class scores to the summary");
	TCLAP::SwitchArg& argJson = cli.addJson();
	if (const auto code = cli.parse(argc, argv)) return *code;
	if (argOut.getValue().empty()) return cli.usageError("missing --out");
	if (argRawlog.getValue().empty() == arg3dtk.getValue().empty())
		return cli.usageError("give either --rawlog or --3dtk");
	const std::string poses = argPoses.getValue();
	const auto poseSource = semnav::MapBuilder::poseSourceFromName(poses);
	if (!poseSource)
		return cli.usageError(
		    "--poses must be odometry, gt or pf, got '" + poses + "'");

	return cli.run(
	    [&]
	    {
		    sections.loadIfGiven(argConfig.getValue());
		    if (!argLocConfig.getValue().empty())
			    semnav::IniSections()
			        .add(
			            s.localization, "",
			            semnav::MappingLocalizer::TOptions::sections())
			        .load(argLocConfig.getValue());
		    if (const auto file = cascades.file())
			    s.cascades =
			        semnav::CascadeDetector::TOptions::fromIniFile(*file);
		    s.poses = *poseSource;
		    s.rawlog = argRawlog.getValue();
		    s.scans3dtk = arg3dtk.getValue();
		    s.gtDir = argGt.getValue();
		    semnav::MapIO::checkTarget(argOut.getValue());
		    semnav::MapBuilder builder(s);
		    semnav::ProgressBar bar(builder.expectedSweeps(), "mapping");
		    builder.run([&](std::size_t done) { bar.update(done); });
		    bar.finish();
		    if (builder.map().sweepsInserted() == 0)  // no 0 x 0 map
			    throw semnav::RawlogError(
			        !builder.readError().empty()
			            ? builder.readError() + " (no map written)"
			            : "no sweeps in " + s.rawlog + " (" +
			                  std::to_string(
			                      builder.sweepsSkippedIncomplete()) +
			                  " incomplete skipped, " +
			                  std::to_string(builder.sweepsFailed()) +
			                  " failed; no map written)");
		    semnav::MapIO::save(builder.map(), argOut.getValue());

		    const auto j = summary(builder, poses, argOut.getValue());
		    if (argJson.getValue())
			    std::cout << j.dump() << std::endl;
		    else
			    printSummary(j, poses);
		    if (!builder.readError().empty())
			    throw semnav::RawlogError(
			        builder.readError() + " (" + mappedOfRead(builder) + ")");
		    return 0;
	    });
}
