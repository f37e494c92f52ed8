/* semnav: semantic navigation from tilting-laser sweeps */
// semnav-plan: CNN path from a point to the nearest object of a label (or
// an object, or a point) on a semantic map (docs/design.md, "Apps").
#include <semnav/common/AtomicFile.h>
#include <semnav/common/CommandLine.h>
#include <semnav/common/IniSections.h>
#include <semnav/map/MapIO.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/planning/GridExport.h>
#include <semnav/planning/PlanRenderer.h>
#include <semnav/planning/SemanticPlanner.h>

#include <iostream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <optional>

namespace
{
/** "X,Y" -> (x, y); nullopt when malformed. */
std::optional<std::pair<double, double>> parseXY(const std::string& s)
{
	const auto comma = s.find(',');
	if (comma == std::string::npos) return std::nullopt;
	try
	{
		std::size_t a = 0, b = 0;
		const double x = std::stod(s.substr(0, comma), &a);
		const double y = std::stod(s.substr(comma + 1), &b);
		if (a != comma || b != s.size() - comma - 1) return std::nullopt;
		return std::make_pair(x, y);
	}
	catch (const std::exception&)
	{
		return std::nullopt;
	}
}

nlohmann::json planJson(
    const semnav::SemanticPlanner::Plan& plan, semnav::CostProfile profile)
{
	nlohmann::json j{{"found", true}};
	j["goal_label"] = plan.goalLabel == semnav::Label::Unknown
	                      ? nullptr
	                      : nlohmann::json(semnav::labelName(plan.goalLabel));
	j["goal_object_id"] = plan.goalObjectId;
	j["cost"] = plan.path.cost;
	j["length_m"] = plan.path.lengthM;
	j["iterations"] = plan.field.iterations;
	j["ms"] = plan.field.milliseconds;
	j["profile"] = semnav::costProfileName(profile);
	j["path"] = nlohmann::json::array();
	for (const auto& p : plan.path.points) j["path"].push_back({p.x, p.y});
	return j;
}

void printPlan(
    const semnav::SemanticPlanner::Plan& plan, const std::string& png)
{
	std::cout << "semnav-plan: path of " << plan.path.lengthM << " m, cost "
	          << plan.path.cost;
	if (plan.goalObjectId)
		std::cout << ", to " << semnav::labelName(plan.goalLabel) << " #"
		          << plan.goalObjectId;
	std::cout << " (" << plan.field.iterations << " passes, "
	          << plan.field.milliseconds << " ms)\n";
	if (!png.empty()) std::cout << "  picture: " << png << "\n";
}
}  // namespace

int main(int argc, char** argv)
{
	semnav::CommandLine cli(
	    "semnav-plan",
	    "Plans the least-cost path (CNN diffusion, paper sec. 3) on a semantic "
	    "map from a start point to the nearest object of a label, to one "
	    "object, or to a point.");
	auto& cmd = cli.cmd();
	TCLAP::ValueArg<std::string> argMap(
	    "", "map", "Map directory (semnav-map); required", false, "", "MAPDIR",
	    cmd);
	TCLAP::ValueArg<std::string> argFrom(
	    "", "from", "Start X,Y (m); required", false, "", "X,Y", cmd);
	TCLAP::ValueArg<std::string> argGoal(
	    "", "goal", "Goal label: the nearest (least-cost) object of it", false,
	    "", "LABEL", cmd);
	TCLAP::ValueArg<int> argObject(
	    "", "object", "Goal object id", false, 0, "ID", cmd);
	TCLAP::ValueArg<std::string> argTo(
	    "", "to", "Goal point X,Y (m)", false, "", "X,Y", cmd);
	TCLAP::ValueArg<std::string> argProfile(
	    "", "profile", "shortest (default) or safe", false, "", "shortest|safe",
	    cmd);
	semnav::CnnPlanner::TOptions cnnOpts;
	semnav::TraversabilityBuilder::TOptions travOpts;
	semnav::SemanticMap::TOptions mapOpts;
	semnav::IniSections sections;
	sections.add(cnnOpts, "CnnPlanner")
	    .add(travOpts, "Traversability")
	    .add(mapOpts, "SemanticMap")
	    .add(mapOpts.cost, "TravelCost");
	TCLAP::ValueArg<std::string>& argConfig =
	    cli.addConfig(sections, "INI file (see config/planning.ini)");
	TCLAP::ValueArg<std::string> argPng(
	    "", "png", "Write a picture of map, u, field and path", false, "",
	    "OUT.png", cmd);
	TCLAP::ValueArg<std::string> argExport(
	    "", "export-grid",
	    "Write PREFIX_u.npy, PREFIX_goal.npy, PREFIX_meta.json", false, "",
	    "PREFIX", cmd);
	TCLAP::SwitchArg& argJson = cli.addJson();
	if (const auto code = cli.parse(argc, argv)) return *code;
	if (argMap.getValue().empty()) return cli.usageError("missing --map");
	const auto from = parseXY(argFrom.getValue());
	if (!from)
		return cli.usageError(
		    "--from must be X,Y in metres, got '" + argFrom.getValue() + "'");
	const int goals = !argGoal.getValue().empty() + argObject.isSet() +
	                  !argTo.getValue().empty();
	if (goals != 1)
		return cli.usageError("give exactly one of --goal, --object, --to");
	std::optional<std::pair<double, double>> to;
	if (!argTo.getValue().empty() && !(to = parseXY(argTo.getValue())))
		return cli.usageError(
		    "--to must be X,Y in metres, got '" + argTo.getValue() + "'");

	std::optional<semnav::CostProfile> givenProfile;
	if (!argProfile.getValue().empty())
	{
		try
		{
			givenProfile = semnav::costProfileFromName(argProfile.getValue());
		}
		catch (const semnav::PlanningError& e)
		{
			return cli.usageError(std::string("--profile: ") + e.what());
		}
	}

	const bool json = argJson.getValue();
	return cli.run(
	    [&]
	    {
		    sections.loadIfGiven(argConfig.getValue());
		    const semnav::CostProfile profile =
		        givenProfile.value_or(travOpts.profile);
		    const semnav::Label label =
		        argGoal.getValue().empty()
		            ? semnav::Label::Unknown
		            : semnav::labelFromName(argGoal.getValue());

		    semnav::SemanticMap map(mapOpts);
		    semnav::MapIO::load(argMap.getValue(), map);
		    const semnav::SemanticPlanner planner(map, cnnOpts, travOpts);
		    nlohmann::json j{{"found", false}};
		    try
		    {
			    semnav::SemanticPlanner::Plan plan;
			    if (label != semnav::Label::Unknown)
				    plan = planner.toLabel(
				        from->first, from->second, label, profile);
			    else if (argObject.isSet())
				    plan = planner.toObject(
				        from->first, from->second, argObject.getValue(),
				        profile);
			    else
				    plan = planner.toPoint(
				        from->first, from->second, to->first, to->second,
				        profile);
			    if (!argPng.getValue().empty())
			    {
				    std::vector<uchar> buf;
				    cv::imencode(
				        ".png", semnav::PlanRenderer::render(map, plan), buf);
				    semnav::writeFileAtomically(
				        argPng.getValue(), std::string(buf.begin(), buf.end()));
			    }
			    if (!argExport.getValue().empty())
				    semnav::exportPlanGrids(argExport.getValue(), plan);
			    if (json)
				    std::cout << planJson(plan, profile).dump() << std::endl;
			    else
				    printPlan(plan, argPng.getValue());
		    }
		    catch (const semnav::PlanningError& e)
		    {
			    if (json)
			    {
				    j["error"] = e.what();
				    std::cout << j.dump() << std::endl;
			    }
			    throw;
		    }
		    return 0;
	    });
}
