/* semnav: semantic navigation from tilting-laser sweeps */
// semnav-nav: headless simulated run of a semantic command ("go to the
// nearest wastebasket") through MRPT's reactive navigator on a semantic map
// (docs/design.md, "Apps").
#include <mrpt/config/CConfigFile.h>
#include <mrpt/math/wrap2pi.h>
#include <semnav/common/AtomicFile.h>
#include <semnav/common/CommandLine.h>
#include <semnav/common/ConfigChecks.h>
#include <semnav/common/Error.h>
#include <semnav/localization/MappingLocalizer.h>
#include <semnav/map/MapIO.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/nav/NavCommand.h>
#include <semnav/nav/NavigationConfig.h>
#include <semnav/nav/NavigationRenderer.h>
#include <semnav/nav/SceneMapBuilder.h>
#include <semnav/nav/SimulatedNavigation.h>
#include <semnav/nav/StopAndScanLocalizer.h>
#include <semnav/perception/PerceptionPipeline.h>
#include <semnav/sim/SceneLoader.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <optional>
#include <sstream>

namespace
{
/** "X,Y,YAW_DEG" -> pose (yaw in rad); nullopt when malformed. */
std::optional<mrpt::math::TPose2D> parsePose(const std::string& s)
{
	std::stringstream ss(s);
	std::vector<double> v;
	for (std::string t; std::getline(ss, t, ',');)
	{
		try
		{
			std::size_t n = 0;
			v.push_back(std::stod(t, &n));
			if (n != t.size()) return std::nullopt;
		}
		catch (const std::exception&)
		{
			return std::nullopt;
		}
	}
	if (v.size() != 3 || !std::isfinite(v[0]) || !std::isfinite(v[1]) ||
	    !std::isfinite(v[2]))
		return std::nullopt;
	return mrpt::math::TPose2D(v[0], v[1], v[2] * M_PI / 180);
}

std::string defaultConfig(const std::string& name)
{
	return std::string(SEMNAV_SOURCE_DIR) + "/config/" + name;
}
}  // namespace

int main(int argc, char** argv)
{
	semnav::CommandLine cli(
	    "semnav-nav",
	    "Headless simulated navigation: plans with the CNN planner on a "
	    "semantic map and drives a simulated differential-drive robot in the "
	    "scene through MRPT's reactive navigator (replanning when blocked).");
	auto& cmd = cli.cmd();
	TCLAP::ValueArg<std::string> argMap(
	    "", "map", "Map directory (semnav-map); required", false, "", "MAPDIR",
	    cmd);
	TCLAP::ValueArg<std::string> argScene(
	    "", "scene", "Scene the robot drives in (YAML); required", false, "",
	    "S.yaml", cmd);
	TCLAP::ValueArg<std::string> argStart(
	    "", "start", "Start pose X,Y,YAW_DEG; required", false, "",
	    "X,Y,YAW_DEG", cmd);
	TCLAP::ValueArg<std::string> argCommand(
	    "", "command",
	    "\"go to the nearest <label>\", \"go to <label> <id>\" or "
	    "\"go to <x> <y>\"",
	    false, "", "TEXT", cmd);
	TCLAP::ValueArg<std::string> argGoal(
	    "", "goal", "Same as --command \"go to the nearest LABEL\"", false, "",
	    "LABEL", cmd);
	TCLAP::ValueArg<std::string> argOut(
	    "", "out",
	    "Write navigation.reactivenavlog (navlog-viewer) and navigation.png",
	    false, "", "DIR", cmd);
	TCLAP::ValueArg<std::string> argConfig(
	    "", "config", "Navigation INI (default: config/navigation.ini)", false,
	    defaultConfig("navigation.ini"), "N.ini", cmd);
	TCLAP::ValueArg<std::string> argPlanning(
	    "", "planning-config", "Planning INI (default: config/planning.ini)",
	    false, defaultConfig("planning.ini"), "P.ini", cmd);
	TCLAP::MultiArg<std::string> argSceneInstances(
	    "", "instances-from-scene",
	    "Add the scene's objects of LABEL to the map as instances (ground "
	    "truth; for maps whose detector has not found them)",
	    false, "LABEL", cmd);
	TCLAP::ValueArg<std::string> argGtMap(
	    "", "gt-map",
	    "Instead of --map, the ground-truth map of this scene (usually the "
	    "--scene file; another scene makes the map wrong on purpose)",
	    false, "", "S.yaml", cmd);
	TCLAP::ValueArg<std::string> argLocalize(
	    "", "localize",
	    "The robot does not know its pose: it localizes itself in the map "
	    "by stop-and-scan sweeps (global: anywhere in the map's free space; "
	    "tracking: around --start-guess) and navigates on that estimate and "
	    "its odometry; --start stays the true pose",
	    false, "", "global|tracking", cmd);
	TCLAP::ValueArg<std::string> argStartGuess(
	    "", "start-guess", "Rough start pose for --localize tracking", false,
	    "", "X,Y,YAW_DEG", cmd);
	TCLAP::ValueArg<std::string> argLocConfig(
	    "", "loc-config", "Localization INI (default: config/localization.ini)",
	    false, defaultConfig("localization.ini"), "L.ini", cmd);
	TCLAP::ValueArg<std::string> argPerceptionConfig(
	    "", "perception-config",
	    "Perception INI for --localize (default: config/perception.ini)", false,
	    defaultConfig("perception.ini"), "P.ini", cmd);
	TCLAP::SwitchArg argJson(
	    "", "json", "Print a JSON summary on stdout", cmd, false);
	if (const auto code = cli.parse(argc, argv)) return *code;
	const bool gtMap = !argGtMap.getValue().empty();
	if (argMap.getValue().empty() == !gtMap)
		return cli.usageError("give exactly one of --map, --gt-map");
	if (argScene.getValue().empty()) return cli.usageError("missing --scene");
	const auto start = parsePose(argStart.getValue());
	if (!start)
		return cli.usageError(
		    "--start must be X,Y,YAW_DEG, got '" + argStart.getValue() + "'");
	if (argCommand.getValue().empty() == argGoal.getValue().empty())
		return cli.usageError("give exactly one of --command, --goal");
	std::optional<semnav::StopAndScanLocalizer::Mode> locMode;
	if (!argLocalize.getValue().empty())
	{
		if (argLocalize.getValue() != "global" &&
		    argLocalize.getValue() != "tracking")
			return cli.usageError(
			    "--localize must be global or tracking, got '" +
			    argLocalize.getValue() + "'");
		locMode =
		    semnav::StopAndScanLocalizer::modeFromName(argLocalize.getValue());
	}
	std::optional<mrpt::math::TPose2D> guess;
	if (!argStartGuess.getValue().empty())
	{
		guess = parsePose(argStartGuess.getValue());
		if (!guess)
			return cli.usageError(
			    "--start-guess must be X,Y,YAW_DEG, got '" +
			    argStartGuess.getValue() + "'");
	}
	if (locMode == semnav::StopAndScanLocalizer::Mode::Tracking && !guess)
		return cli.usageError("--localize tracking needs --start-guess");
	if (guess && locMode != semnav::StopAndScanLocalizer::Mode::Tracking)
		return cli.usageError("--start-guess needs --localize tracking");

	const bool json = argJson.getValue();
	return cli.run(
	    [&]
	    {
		    const semnav::NavCommand command =
		        argGoal.getValue().empty()
		            ? semnav::NavCommand::parse(argCommand.getValue())
		            : semnav::NavCommand::nearest(
		                  semnav::labelFromName(argGoal.getValue()));
		    const auto config = semnav::NavigationConfig::load(
		        argConfig.getValue(), argPlanning.getValue());
		    const semnav::Scene scene =
		        semnav::SceneLoader::loadFile(argScene.getValue());
		    semnav::SemanticMap map(config.map);
		    if (gtMap)
			    semnav::SceneMapBuilder::build(
			        semnav::SceneLoader::loadFile(argGtMap.getValue()), map);
		    else
			    semnav::MapIO::load(argMap.getValue(), map);
		    std::vector<std::string> added;  // labels taken from the scene
		    for (const auto& name : argSceneInstances.getValue())
		    {
			    const semnav::Label l = semnav::labelFromName(name);
			    if (map.instances(l).empty() &&
			        semnav::SceneMapBuilder::addInstances(scene, l, map) > 0)
				    added.push_back(name);
		    }

		    std::string navlog, png;
		    if (!argOut.getValue().empty())
		    {
			    semnav::createDirectories(argOut.getValue());
			    navlog = (std::filesystem::path(argOut.getValue()) /
			              "navigation.reactivenavlog")
			                 .string();
			    png = (std::filesystem::path(argOut.getValue()) /
			           "navigation.png")
			              .string();
		    }
		    semnav::SimulatedNavigation sim(map, scene, config);
		    std::unique_ptr<semnav::StopAndScanLocalizer> localizer;
		    if (locMode)
		    {
			    semnav::MappingLocalizer::TOptions locOpts;
			    locOpts.loadFromConfigFile(
			        *semnav::openIniFile(
			            argLocConfig.getValue(),
			            semnav::MappingLocalizer::TOptions::sections()),
			        "");
			    semnav::PerceptionPipeline::TOptions percOpts;
			    percOpts.loadFromConfigFile(
			        *semnav::openIniFile(
			            argPerceptionConfig.getValue(),
			            semnav::PerceptionPipeline::sections()),
			        "");
			    localizer = std::make_unique<semnav::StopAndScanLocalizer>(
			        scene, map, config.stopAndScan, locOpts, percOpts);
			    sim.setLocalization(localizer.get(), *locMode, guess);
		    }
		    const auto r = sim.run(command, *start, navlog);
		    if (!png.empty())
		    {
			    std::vector<uchar> buf;
			    cv::imencode(
			        ".png", semnav::NavigationRenderer::render(map, r), buf);
			    semnav::writeFileAtomically(
			        png, std::string(buf.begin(), buf.end()));
		    }

		    nlohmann::json j;
		    j["success"] = r.success;
		    j["command"] = r.command.text();
		    j["reason"] = semnav::SemanticNavigator::stopReasonName(r.reason);
		    j["message"] = r.message;
		    if (r.objectId)
			    j["reached_object"] = {
			        {"id", r.objectId},
			        {"label", semnav::labelName(r.objectLabel)},
			        {"x", r.objectXY.x},
			        {"y", r.objectXY.y}};
		    else
			    j["reached_object"] = nullptr;
		    j["final_pose"] = {
		        r.finalPose.x, r.finalPose.y, r.finalPose.phi * 180 / M_PI};
		    j["distance_to_object_m"] = r.distanceToGoal;
		    j["collisions"] = r.collisions;
		    j["sim_time_s"] = r.simTime;
		    j["replans"] = r.replans;
		    j["path_length_m"] =
		        r.plans.empty() ? 0.0 : r.plans.front().lengthM;
		    j["wall_s"] = r.wallSeconds;
		    j["median_step_ms"] = r.medianStepMs;
		    j["navlog"] = navlog.empty() ? nlohmann::json(nullptr)
		                                 : nlohmann::json(navlog);
		    j["png"] =
		        png.empty() ? nlohmann::json(nullptr) : nlohmann::json(png);
		    // Every instance of the label with the planner's cost from the
		    // start (the reached one should be the cheapest).
		    if (command.kind == semnav::NavCommand::Kind::NearestLabel)
		    {
			    semnav::SemanticPlanner planner(
			        map, config.cnn, config.traversability);
			    j["instances"] = nlohmann::json::array();
			    for (const auto& o : map.instances(command.label))
			    {
				    nlohmann::json e{
				        {"id", o.id},
				        {"euclidean_m",
				         std::hypot(
				             o.centroid.x - start->x, o.centroid.y - start->y)},
				        {"cost", nullptr}};
				    try
				    {
					    e["cost"] =
					        planner
					            .toObject(
					                start->x, start->y, o.id,
					                semnav::costProfileFromName(
					                    config.navigator.profile == "planning"
					                        ? semnav::costProfileName(
					                              config.traversability.profile)
					                        : config.navigator.profile))
					            .path.cost;
				    }
				    catch (const semnav::PlanningError&)
				    {
				    }
				    j["instances"].push_back(e);
			    }
		    }
		    j["instances_from_scene"] = added;
		    if (r.localization)
		    {
			    const auto& l = *r.localization;
			    nlohmann::json recs = nlohmann::json::array();
			    for (const auto& x : l.records)
				    recs.push_back(
				        {{"segments", x.segments},
				         {"std_xy_m", x.stdXY},
				         {"std_yaw_deg", x.stdYaw * 180 / M_PI},
				         {"error_xy_m", x.errorXY},
				         {"error_yaw_deg", x.errorYaw * 180 / M_PI},
				         {"particles", x.particles},
				         {"update_ms", x.updateMs},
				         {"uniqueness",
				          x.checked ? nlohmann::json{{"score", x.score},
				                                     {"rival_score", x.rivalScore},
				                                     {"rival",
				                                      {x.rival.x, x.rival.y,
				                                       x.rival.phi * 180 / M_PI}},
				                                     {"ms", x.checkMs}}
				                    : nlohmann::json(nullptr)},
				         {"weight_near", x.massNear},
				         {"inliers", x.inliers},
				         {"converged", x.converged},
				         {"ms", x.ms}});
			    nlohmann::json rescans = nlohmann::json::array();
			    for (const auto& x : r.rescans)
				    rescans.push_back(
				        {{"segments", x.segments},
				         {"converged", x.converged},
				         {"inliers", x.inliers},
				         {"error_xy_m", x.errorXY},
				         {"error_yaw_deg", x.errorYaw * 180 / M_PI}});
			    j["localization"] = {
			        {"mode", semnav::StopAndScanLocalizer::modeName(l.mode)},
			        {"sweeps", l.sweeps},
			        {"converged", l.converged},
			        {"estimate",
			         {l.estimate.x, l.estimate.y, l.estimate.phi * 180 / M_PI}},
			        {"truth", {l.truth.x, l.truth.y, l.truth.phi * 180 / M_PI}},
			        {"error_xy_m", l.errorXY},
			        {"error_yaw_deg", l.errorYaw * 180 / M_PI},
			        {"ms", l.ms},
			        {"per_sweep", recs},
			        {"rescans", rescans},
			        {"recoveries", r.recoveries}};
			    if (!r.estimatedTrajectory.empty())
			    {
				    const auto& e = r.estimatedTrajectory.back();
				    j["localization"]["final_estimate"] = {
				        e.x, e.y, e.phi * 180 / M_PI};
				    j["localization"]["final_error_xy_m"] =
				        std::hypot(e.x - r.finalPose.x, e.y - r.finalPose.y);
				    j["localization"]["final_error_yaw_deg"] =
				        std::abs(
				            mrpt::math::wrapToPi(e.phi - r.finalPose.phi)) *
				        180 / M_PI;
			    }
		    }
		    else
			    j["localization"] = nullptr;
		    if (json)
			    std::cout << j.dump() << std::endl;
		    else
		    {
			    for (const auto& a : added)
				    std::printf(
				        "semnav-nav: the map has no %s: the scene's (ground "
				        "truth) stand in\n",
				        a.c_str());
			    std::printf(
			        "semnav-nav: %s: %s", r.command.text().c_str(),
			        r.success ? "reached" : r.message.c_str());
			    if (r.objectId)
				    std::printf(
				        " %s %d at (%.2f, %.2f)",
				        semnav::labelName(r.objectLabel).c_str(), r.objectId,
				        r.objectXY.x, r.objectXY.y);
			    std::printf(
			        "\n  final pose (%.2f, %.2f, %.0f deg), %.2f m from it, "
			        "%d collisions, %.1f s simulated (%.1f s wall), %d "
			        "replans\n",
			        r.finalPose.x, r.finalPose.y, r.finalPose.phi * 180 / M_PI,
			        r.distanceToGoal, r.collisions, r.simTime, r.wallSeconds,
			        r.replans);
			    if (r.localization)
				    std::printf(
				        "  localization (%s): %d sweeps, estimate (%.2f, %.2f, "
				        "%.1f deg), error %.3f m %.2f deg, %.0f ms\n",
				        semnav::StopAndScanLocalizer::modeName(
				            r.localization->mode)
				            .c_str(),
				        r.localization->sweeps, r.localization->estimate.x,
				        r.localization->estimate.y,
				        r.localization->estimate.phi * 180 / M_PI,
				        r.localization->errorXY,
				        r.localization->errorYaw * 180 / M_PI,
				        r.localization->ms);
			    if (!png.empty())
				    std::printf(
				        "  picture: %s\n  navlog (navlog-viewer): %s\n",
				        png.c_str(), navlog.c_str());
		    }
		    if (!r.success)
		    {
			    std::cerr << "semnav-nav: navigation failed: " << r.message
			              << std::endl;
			    return 1;
		    }
		    return 0;
	    });
}
