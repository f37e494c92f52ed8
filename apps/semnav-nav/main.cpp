/* semnav: semantic navigation from tilting-laser sweeps */
// semnav-nav: headless simulated run of a semantic command ("go to the
// nearest wastebasket") through MRPT's reactive navigator on a semantic map
// (docs/design.md, "Apps").
#include <mrpt/math/wrap2pi.h>
#include <semnav/common/CascadeArgs.h>
#include <semnav/common/CommandLine.h>
#include <semnav/common/IniSections.h>
#include <semnav/common/ShippedConfig.h>
#include <semnav/nav/NavCommand.h>
#include <semnav/nav/NavLogFile.h>
#include <semnav/navsim/NavigationRun.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

namespace
{
/** Radians to degrees, as the summary always computed them. */
double deg(double rad)
{
	return rad * 180 / M_PI;
}

nlohmann::json poseJson(const mrpt::math::TPose2D& p)
{
	return {p.x, p.y, deg(p.phi)};
}

nlohmann::json arrivalsJson(const semnav::SimulatedNavigation::Result& r)
{
	nlohmann::json out = nlohmann::json::array();
	for (const auto& a : r.arrivals)
		out.push_back(
		    {{"confirmed", a.confirmed},
		     {"reason", a.reason},
		     {"relocalized", a.relocalized},
		     {"object_distance_m", std::isfinite(a.objectDistance)
		                               ? nlohmann::json(a.objectDistance)
		                               : nlohmann::json(nullptr)},
		     {"label_points", a.labelPoints},
		     {"object_checked", a.objectChecked},
		     {"estimate", poseJson(a.estimate)}});
	return out;
}

nlohmann::json localizationJson(const semnav::SimulatedNavigation::Result& r)
{
	const auto& l = *r.localization;
	nlohmann::json recs = nlohmann::json::array();
	for (const auto& x : l.records)
		recs.push_back(
		    {{"segments", x.segments},
		     {"std_xy_m", x.stdXY},
		     {"std_yaw_deg", deg(x.stdYaw)},
		     {"error_xy_m", x.errorXY},
		     {"error_yaw_deg", deg(x.errorYaw)},
		     {"particles", x.particles},
		     {"update_ms", x.updateMs},
		     {"uniqueness",
		      x.checked
		          ? nlohmann::
		                json{{"score", x.score}, {"rival_score", x.rivalScore}, {"rival", poseJson(x.rival)}, {"ms", x.checkMs}}
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
		     {"error_yaw_deg", deg(x.errorYaw)}});
	nlohmann::json j = {
	    {"mode", semnav::StopAndScanLocalizer::modeName(l.mode)},
	    {"sweeps", l.sweeps},
	    {"drives_to_look", l.drives},
	    {"drive_to_look_m", l.driveLength},
	    {"converged", l.converged},
	    {"estimate", poseJson(l.estimate)},
	    {"truth", poseJson(l.truth)},
	    {"error_xy_m", l.errorXY},
	    {"error_yaw_deg", deg(l.errorYaw)},
	    {"ms", l.ms},
	    {"per_sweep", recs},
	    {"rescans", rescans},
	    {"recoveries", r.recoveries},
	    {"arrival_checks", arrivalsJson(r)}};
	if (!r.estimatedTrajectory.empty())
	{
		const auto& e = r.estimatedTrajectory.back();
		j["final_estimate"] = poseJson(e);
		j["final_error_xy_m"] =
		    std::hypot(e.x - r.finalPose.x, e.y - r.finalPose.y);
		j["final_error_yaw_deg"] =
		    deg(std::abs(mrpt::math::wrapToPi(e.phi - r.finalPose.phi)));
	}
	return j;
}

nlohmann::json summaryJson(
    const semnav::NavigationRun& run,
    const semnav::SimulatedNavigation::Result& r,
    const std::vector<semnav::NavigationRun::InstanceCost>& costs)
{
	const auto pathOrNull = [](const std::string& p)
	{ return p.empty() ? nlohmann::json(nullptr) : nlohmann::json(p); };
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
	j["final_pose"] = poseJson(r.finalPose);
	j["distance_to_object_m"] = r.distanceToGoal;
	const auto orNull = [](const std::optional<double>& v)
	{ return v ? nlohmann::json(*v) : nlohmann::json(nullptr); };
	j["believed_reached"] = r.believedReached;
	j["believed_final_pose"] = poseJson(r.believedFinalPose);
	j["true_final_pose"] = poseJson(r.finalPose);
	j["true_object"] = r.trueObjectId ? nlohmann::json{{"id", r.trueObjectId},
	                                                   {"x", r.trueObjectXY.x},
	                                                   {"y", r.trueObjectXY.y}}
	                                  : nlohmann::json(nullptr);
	j["true_distance_m"] = orNull(r.trueDistance);
	j["true_nearest_of_label_m"] = orNull(r.trueNearestOfLabel);
	j["arrival_tolerance_m"] = r.arrivalTolerance;
	j["false_arrival"] = r.falseArrival;
	j["collisions"] = r.collisions;
	j["sim_time_s"] = r.simTime;
	j["replans"] = r.replans;
	j["path_length_m"] = r.plans.empty() ? 0.0 : r.plans.front().lengthM;
	j["wall_s"] = r.wallSeconds;
	j["median_step_ms"] = r.medianStepMs;
	j["navlog"] = pathOrNull(run.navlogPath());
	j["png"] = pathOrNull(run.pngPath());
	if (r.command.kind == semnav::NavCommand::Kind::NearestLabel)
	{
		j["instances"] = nlohmann::json::array();
		for (const auto& c : costs)
			j["instances"].push_back(
			    {{"id", c.id},
			     {"euclidean_m", c.euclidean},
			     {"cost",
			      c.cost ? nlohmann::json(*c.cost) : nlohmann::json(nullptr)}});
	}
	j["instances_from_scene"] = run.addedFromScene();
	j["localization"] =
	    r.localization ? localizationJson(r) : nlohmann::json(nullptr);
	return j;
}

void printSummary(
    const semnav::NavigationRun& run,
    const semnav::SimulatedNavigation::Result& r)
{
	for (const auto& a : run.addedFromScene())
		std::printf(
		    "semnav-nav: the map has no %s: the scene's (ground truth) stand "
		    "in\n",
		    a.c_str());
	char object[160] = "";
	if (r.objectId)
		std::snprintf(
		    object, sizeof(object), " %s %d at (%.2f, %.2f)",
		    semnav::labelName(r.objectLabel).c_str(), r.objectId, r.objectXY.x,
		    r.objectXY.y);
	std::printf(
	    "semnav-nav: %s: %s", r.command.text().c_str(),
	    r.outcome(object).c_str());
	std::printf(
	    "\n  final pose (%.2f, %.2f, %.0f deg), %.2f m from it, %d "
	    "collisions, %.1f s simulated (%.1f s wall), %d replans\n",
	    r.finalPose.x, r.finalPose.y, deg(r.finalPose.phi), r.distanceToGoal,
	    r.collisions, r.simTime, r.wallSeconds, r.replans);
	if (const auto& l = r.localization)
		std::printf(
		    "  localization (%s): %d sweeps, estimate (%.2f, %.2f, %.1f deg), "
		    "error %.3f m %.2f deg, %.0f ms\n",
		    semnav::StopAndScanLocalizer::modeName(l->mode).c_str(), l->sweeps,
		    l->estimate.x, l->estimate.y, deg(l->estimate.phi), l->errorXY,
		    deg(l->errorYaw), l->ms);
	if (r.localization)
		std::printf(
		    "  believed final pose (%.2f, %.2f, %.0f deg), %s\n",
		    r.believedFinalPose.x, r.believedFinalPose.y,
		    deg(r.believedFinalPose.phi),
		    r.believedReached ? "believed reached" : "not believed reached");
	if (!run.pngPath().empty())
		std::printf(
		    "  picture: %s\n  navlog (navlog-viewer): %s\n",
		    run.pngPath().c_str(), run.navlogPath().c_str());
}
/** --localize MODE and --start-guess X,Y,YAW_DEG into `s`; the usage
 * problem, if any. */
std::optional<std::string> readKidnapping(
    const std::string& at, const std::string& to,
    semnav::NavigationRun::Settings& s)
{
	if (at.empty() != to.empty())
		return std::string("--kidnap-at and --kidnap-to go together");
	if (at.empty()) return std::nullopt;
	char* end = nullptr;
	const double t = std::strtod(at.c_str(), &end);
	if (end == at.c_str() || *end || !(t >= 0))
		return "--kidnap-at must be a time >= 0 (s), got '" + at + "'";
	const auto pose = semnav::CommandLine::parsePose(to);
	if (!pose) return "--kidnap-to must be X,Y,YAW_DEG, got '" + to + "'";
	s.kidnapAt = t;
	s.kidnapTo = *pose;
	return std::nullopt;
}

std::optional<std::string> readLocalization(
    const std::string& mode, const std::string& guess,
    semnav::NavigationRun::Settings& s)
{
	using Mode = semnav::StopAndScanLocalizer::Mode;
	if (!mode.empty())
	{
		if (mode != "global" && mode != "tracking")
			return "--localize must be global or tracking, got '" + mode + "'";
		s.localize = semnav::StopAndScanLocalizer::modeFromName(mode);
	}
	if (!guess.empty())
	{
		s.startGuess = semnav::CommandLine::parsePose(guess);
		if (!s.startGuess)
			return "--start-guess must be X,Y,YAW_DEG, got '" + guess + "'";
	}
	if (s.localize == Mode::Tracking && !s.startGuess)
		return "--localize tracking needs --start-guess";
	if (s.startGuess && s.localize != Mode::Tracking)
		return "--start-guess needs --localize tracking";
	return std::nullopt;
}
}  // namespace

/** semnav-nav's arguments (the CLI's own: --write-config, --json, the
 * cascade arguments are added by their classes). */
struct Arguments
{
	explicit Arguments(TCLAP::CmdLine& c) : cmd(c) {}
	static std::string shipped(const std::string& f)
	{
		return semnav::ShippedConfig::path(f);
	}
	TCLAP::CmdLine& cmd;
	TCLAP::ValueArg<std::string> argMap{
	    "",       "map", "Map directory (semnav-map); required", false, "",
	    "MAPDIR", cmd};
	TCLAP::ValueArg<std::string> argScene{
	    "",    "scene", "Scene the robot drives in (YAML); required",
	    false, "",      "S.yaml",
	    cmd};
	TCLAP::ValueArg<std::string> argStart{
	    "",    "start", "Start pose X,Y,YAW_DEG; required",
	    false, "",      "X,Y,YAW_DEG",
	    cmd};
	TCLAP::ValueArg<std::string> argCommand{
	    "",
	    "command",
	    "\"go to the nearest <label>\", \"go to <label> <id>\" or "
	    "\"go to <x> <y>\"",
	    false,
	    "",
	    "TEXT",
	    cmd};
	TCLAP::ValueArg<std::string> argGoal{
	    "",    "goal", "Same as --command \"go to the nearest LABEL\"",
	    false, "",     "LABEL",
	    cmd};
	TCLAP::ValueArg<std::string> argOut{
	    "",
	    "out",
	    "Write navigation.reactivenavlog (navlog-viewer) and navigation.png",
	    false,
	    "",
	    "DIR",
	    cmd};
	TCLAP::ValueArg<std::string> argConfig{
	    "",      "config", "Navigation INI", false, shipped("navigation.ini"),
	    "N.ini", cmd};
	TCLAP::ValueArg<std::string> argPlanning{
	    "",    "planning-config",       "Planning INI",
	    false, shipped("planning.ini"), "P.ini",
	    cmd};
	TCLAP::ValueArg<std::string> argSimConfig{
	    "",    "sim-config",       "Simulator INI ([SimulatedRobot])",
	    false, shipped("sim.ini"), "S.ini",
	    cmd};
	TCLAP::MultiArg<std::string> argSceneInstances{
	    "",
	    "instances-from-scene",
	    "Add the scene's objects of LABEL to the map as instances (ground "
	    "truth; for maps whose detector has not found them)",
	    false,
	    "LABEL",
	    cmd};
	TCLAP::ValueArg<std::string> argGtMap{
	    "",
	    "gt-map",
	    "Instead of --map, the ground-truth map of this scene (usually the "
	    "--scene file; another scene makes the map wrong on purpose)",
	    false,
	    "",
	    "S.yaml",
	    cmd};
	TCLAP::ValueArg<std::string> argLocalize{
	    "",
	    "localize",
	    "The robot does not know its pose: it localizes itself in the map "
	    "by stop-and-scan sweeps (global: anywhere in the map's free space; "
	    "tracking: around --start-guess) and navigates on that estimate and "
	    "its odometry; --start stays the true pose",
	    false,
	    "",
	    "global|tracking",
	    cmd};
	TCLAP::SwitchArg argVerbose{
	    "", "verbose",
	    "Localization progress on stderr: each sweep, the uniqueness check, "
	    "each drive to look",
	    cmd};
	TCLAP::ValueArg<std::string> argKidnapAt{
	    "",
	    "kidnap-at",
	    "Carry the robot to --kidnap-to at this simulated time (s) while its "
	    "odometry notices nothing",
	    false,
	    "",
	    "T",
	    cmd};
	TCLAP::ValueArg<std::string> argKidnapTo{
	    "",    "kidnap-to", "Where --kidnap-at carries the robot",
	    false, "",          "X,Y,YAW_DEG",
	    cmd};
	TCLAP::ValueArg<std::string> argStartGuess{
	    "",
	    "start-guess",
	    "Rough start pose for --localize tracking",
	    false,
	    "",
	    "X,Y,YAW_DEG",
	    cmd};
	TCLAP::ValueArg<double> argArrivalMargin{
	    "",
	    "arrival-margin",
	    "A believed arrival counts when the robot truly stands within the "
	    "goal region's radius + goal_allowed_distance_m + this margin (m) of "
	    "the scene's object (docs/navigation.md)",
	    false,
	    semnav::SimulationConfig().arrivalMargin,
	    "M",
	    cmd};
	TCLAP::ValueArg<std::string> argLocConfig{"",
	                                          "loc-config",
	                                          "Localization INI",
	                                          false,
	                                          shipped("localization.ini"),
	                                          "L.ini",
	                                          cmd};
	TCLAP::ValueArg<std::string> argPerceptionConfig{
	    "",    "perception-config",       "Perception INI for --localize",
	    false, shipped("perception.ini"), "P.ini",
	    cmd};
};

int main(int argc, char** argv)
{
	semnav::CommandLine cli(
	    "semnav-nav",
	    "Headless simulated navigation: plans with the CNN planner on a "
	    "semantic map and drives a simulated differential-drive robot in the "
	    "scene through MRPT's reactive navigator (replanning when blocked).");
	auto& cmd = cli.cmd();
	Arguments a(cmd);
	semnav::CascadeArgs cascades(cli);
	semnav::NavigationRun::Settings s;
	auto& c = s.config;
	semnav::IniSections localizationSections, perceptionSections, all;
	localizationSections.add(
	    s.localization, "", semnav::MappingLocalizer::TOptions::sections());
	perceptionSections.add(
	    s.perception, "", semnav::PerceptionPipeline::sections());
	all.add(c.navigator, "SemanticNavigator")
	    .add(c.stopAndScan, "StopAndScan")
	    .add(c.robotInterface, "RobotNavInterface")
	    .add(c.sweepObstacles, "SweepObstacles")
	    .add(c.robot, "SimulatedRobot")
	    .add(c.cnn, "CnnPlanner")
	    .add(c.traversability, "Traversability")
	    .add(c.map, "SemanticMap")
	    .add(c.map.cost, "TravelCost")
	    .add(s.localization, "", semnav::MappingLocalizer::TOptions::sections())
	    .add(s.perception, "", semnav::PerceptionPipeline::sections());
	cli.addWriteConfig(all);
	TCLAP::SwitchArg& argJson = cli.addJson();
	if (const auto code = cli.parse(argc, argv)) return *code;
	s.gtMapScene = a.argGtMap.getValue();
	s.mapDir = a.argMap.getValue();
	if (s.mapDir.empty() == s.gtMapScene.empty())
		return cli.usageError("give exactly one of --map, --gt-map");
	s.scene = a.argScene.getValue();
	if (s.scene.empty()) return cli.usageError("missing --scene");
	const auto start = semnav::CommandLine::parsePose(a.argStart.getValue());
	if (!start)
		return cli.usageError(
		    "--start must be X,Y,YAW_DEG, got '" + a.argStart.getValue() + "'");
	if (a.argCommand.getValue().empty() == a.argGoal.getValue().empty())
		return cli.usageError("give exactly one of --command, --goal");
	if (const auto problem = readKidnapping(
	        a.argKidnapAt.getValue(), a.argKidnapTo.getValue(), s))
		return cli.usageError(*problem);
	if (const auto problem = readLocalization(
	        a.argLocalize.getValue(), a.argStartGuess.getValue(), s))
		return cli.usageError(*problem);
	if (!(a.argArrivalMargin.getValue() >= 0))
		return cli.usageError("--arrival-margin must be >= 0");
	s.instancesFromScene = a.argSceneInstances.getValue();
	s.outDir = a.argOut.getValue();
	s.verbose = a.argVerbose.getValue();

	return cli.run(
	    [&]
	    {
		    const semnav::NavCommand command =
		        a.argGoal.getValue().empty()
		            ? semnav::NavCommand::parse(a.argCommand.getValue())
		            : semnav::NavCommand::nearest(
		                  semnav::labelFromName(a.argGoal.getValue()));
		    if (const auto file = cascades.file())
			    s.cascades =
			        semnav::CascadeDetector::TOptions::fromIniFile(*file);
		    s.config = semnav::SimulationConfig::load(
		        a.argConfig.getValue(), a.argPlanning.getValue(),
		        a.argSimConfig.getValue());
		    s.config.arrivalMargin = a.argArrivalMargin.getValue();
		    if (s.localize)
		    {
			    localizationSections.load(a.argLocConfig.getValue());
			    perceptionSections.load(a.argPerceptionConfig.getValue());
		    }
		    semnav::NavigationRun run(s);
		    semnav::NavLogFile::removeOnTermination(run.navlogPath());
		    const auto r = run.run(command, *start);
		    if (argJson.getValue())
			    std::cout << summaryJson(
			                     run, r, run.instanceCosts(command, *start))
			                     .dump()
			              << std::endl;
		    else
			    printSummary(run, r);
		    if (!r.success)
		    {
			    std::cerr << "semnav-nav: navigation failed: " << r.outcome()
			              << std::endl;
			    return 1;
		    }
		    return 0;
	    });
}
