/* semnav: semantic navigation from tilting-laser sweeps */
// semnav-sim: simulates a tilting LMS200 in a scene and writes a rawlog
// with ground truth (docs/design.md, "Apps").
#include <semnav/common/AtomicFile.h>
#include <semnav/common/CommandLine.h>
#include <semnav/common/Error.h>
#include <semnav/common/IniSections.h>
#include <semnav/common/ProgressBar.h>
#include <semnav/sim/SceneGenerator.h>
#include <semnav/sim/SceneLoader.h>
#include <semnav/sim/SimulatedRobotOptions.h>
#include <semnav/sim/SimulationRunner.h>

#include <cstdint>
#include <exception>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace
{
/** The scene's objects with their centres and ground-truth pixels per sweep
 * (how the map's objects are scored: scripts/eval-generated --map). */
nlohmann::json objectsJson(
    const semnav::Scene& scene, const semnav::SimulationResult& res)
{
	nlohmann::json objs = nlohmann::json::array();
	for (const auto& o : scene.objects)
	{
		nlohmann::json pixels = nlohmann::json::array();
		for (const auto& sweep : res.objectPixels)
			pixels.push_back(sweep.at(o.id));
		const auto c = o.centre();
		objs.push_back(
		    {{"id", o.id},
		     {"label", semnav::labelName(o.label)},
		     {"x", c.x},
		     {"y", c.y},
		     {"sweep_pixels", pixels}});
	}
	return objs;
}
}  // namespace

int main(int argc, char** argv)
{
	semnav::CommandLine cli(
	    "semnav-sim",
	    "Simulates a SICK LMS200 on a tilting head (stop-and-scan) in a scene "
	    "and writes <out>/<name>.rawlog, <name>.gt.txt and <name>.labels/. "
	    "With --generate, writes a procedural scene file to --out instead "
	    "(docs/generated-scenes.md).");
	auto& cmd = cli.cmd();
	TCLAP::ValueArg<std::string> argScene(
	    "", "scene", "Scene file (YAML); required", false, "", "S.yaml", cmd);
	TCLAP::ValueArg<std::string> argOut(
	    "", "out",
	    "Output directory (created if needed); with --generate the scene "
	    "file to write; required",
	    false, "", "DIR", cmd);
	TCLAP::ValueArg<std::string> argGenerate(
	    "", "generate",
	    "Write a procedural scene of this kind (indoor or outdoor) for --seed "
	    "to --out instead of simulating",
	    false, "", "KIND", cmd);
	TCLAP::ValueArg<std::string> argSeed(
	    "", "seed",
	    "Random seed (terrain, range and odometry noise); default 0", false,
	    "0", "N", cmd);
	semnav::SimulationRunner::TOptions opts;
	// [SimulatedRobot] of sim.ini is semnav-nav's; checked, not used here.
	semnav::SimulatedRobotOptions robotOptions;
	semnav::IniSections sections;
	sections.add(opts, "Simulator").add(robotOptions, "SimulatedRobot");
	TCLAP::ValueArg<std::string>& argConfig =
	    cli.addConfig(sections, "INI file (see config/sim.ini)");
	TCLAP::SwitchArg& argJson = cli.addJson();
	if (const auto code = cli.parse(argc, argv)) return *code;
	const auto seedValue =
	    semnav::CommandLine::parseUnsigned(argSeed.getValue());
	if (!seedValue)
		return cli.usageError(
		    "--seed must be a non-negative integer, got '" +
		    argSeed.getValue() + "'");
	if (argGenerate.isSet())
	{
		if (argScene.isSet())
			return cli.usageError("give --generate or --scene, not both");
		if (argOut.getValue().empty()) return cli.usageError("missing --out");
		semnav::SceneGenerator::TOptions gen;
		gen.seed = *seedValue;
		try
		{
			gen.kind =
			    semnav::SceneGenerator::kindFromName(argGenerate.getValue());
		}
		catch (const std::exception& e)
		{
			return cli.usageError(std::string("--generate: ") + e.what());
		}
		return cli.run(
		    [&]
		    {
			    semnav::writeFileAtomically(
			        argOut.getValue(), semnav::SceneGenerator(gen).generate());
			    return 0;
		    });
	}
	for (auto* a : {&argScene, &argOut})
		if (a->getValue().empty())
			return cli.usageError("missing --" + a->getName());
	const std::string scenePath = argScene.getValue();
	const std::string outDir = argOut.getValue();
	const std::string configPath = argConfig.getValue();
	const uint64_t seed = *seedValue;
	const bool json = argJson.getValue();

	return cli.run(
	    [&]
	    {
		    sections.loadIfGiven(configPath);
		    const semnav::Scene scene =
		        semnav::SceneLoader::loadFile(scenePath);
		    const semnav::SimulationRunner runner(scene, opts, seed);

		    semnav::ProgressBar bar(
		        scene.trajectory.size(), "simulating " + scene.name);
		    const auto res = runner.run(
		        outDir,
		        [&](std::size_t done, std::size_t) { bar.update(done); });
		    bar.finish();

		    if (json)
		    {
			    nlohmann::json j;
			    j["rawlog"] = res.rawlogPath;
			    j["sweeps"] = res.sweeps;
			    j["scans"] = res.scans;
			    j["gt"] = res.gtPath;
			    j["labels_dir"] = res.labelsDir;
			    j["objects"] = objectsJson(scene, res);
			    std::cout << j.dump() << std::endl;
		    }
		    else
		    {
			    std::cout << "scene " << scene.name << " (seed " << seed
			              << "): " << res.sweeps << " sweeps, " << res.scans
			              << " scan lines, " << res.odometry
			              << " odometry entries\n"
			              << "  rawlog:       " << res.rawlogPath << "\n"
			              << "  ground truth: " << res.gtPath << "\n"
			              << "  label images: " << res.labelsDir
			              << "/sweep_NNNN.png\n";
		    }
		    return 0;
	    });
}
