/* semnav: semantic navigation from tilting-laser sweeps */
// The semnav-map command line's defaults: the whole pipeline (rules,
// cascades, 3D checks) with the shipped config/cascade.ini and no flags;
// --no-cascades; a missing or corrupt cascade or shape model is one line
// naming the file, exit 1; --write-config writes a file --config loads.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "../TestPaths.h"
#include "AppRunner.h"

using namespace semnav::test;
namespace fs = std::filesystem;

namespace
{
const std::set<std::string> kDetected = {"washbasin", "wastebasket", "stairs"};
const fs::path kMapCliTmp = fs::temp_directory_path() /
                            ("semnav_map_cli_" + std::to_string(::getpid()));

/** The office simulated once (seed 1, as the README's tour). */
const fs::path& office()
{
	static const fs::path rawlog = []
	{
		const fs::path d = kMapCliTmp / "office";
		const AppRun r = runApp(
		    "semnav-sim", "--scene " + test::kSourceDir +
		                      "/datasets/office/office.yaml --out " +
		                      d.string() + " --seed 1");
		EXPECT_EQ(r.code, 0) << r.err;
		return d / "office.rawlog";
	}();
	return rawlog;
}

/** Labels of the objects in semnav-map's --json summary. */
std::multiset<std::string> objectLabels(const std::string& json)
{
	std::multiset<std::string> labels;
	const auto j = nlohmann::json::parse(json);
	for (const auto& o : j.at("objects"))
		labels.insert(o.at("label").get<std::string>());
	return labels;
}

/** A copy of config/cascade.ini in kMapCliTmp whose `key` of every class names
 * `file` (the other model paths made absolute). */
fs::path cascadeIniNaming(
    const std::string& key, const fs::path& file, const std::string& name)
{
	std::ifstream in(test::kSourceDir + "/config/cascade.ini");
	const fs::path ini = kMapCliTmp / name;
	std::ofstream out(ini);
	for (std::string line; std::getline(in, line);)
	{
		if (line.rfind(key + " = ", 0) == 0)
			line = key + " = " + file.string();
		else if (const auto at = line.find(" = ../"); at != std::string::npos)
			line = line.substr(0, at) + " = " + test::kSourceDir + "/config/" +
			       line.substr(at + 3);
		out << line << "\n";
	}
	return ini;
}

AppRun mapWith(const std::string& args)
{
	return runApp(
	    "semnav-map", "--rawlog " + office().string() + " --out " +
	                      (kMapCliTmp / "map").string() + " --json " + args);
}

class SemnavMapCli : public ::testing::Test
{
protected:
	static void SetUpTestSuite() { fs::create_directories(kMapCliTmp); }
	static void TearDownTestSuite() { fs::remove_all(kMapCliTmp); }
};
}  // namespace

TEST_F(SemnavMapCli, DefaultsDetectTheOfficesObjects)
{
	const AppRun r = mapWith("");
	ASSERT_EQ(r.code, 0) << r.err;
	const auto labels = objectLabels(r.out);
	for (const auto& l : kDetected)
		EXPECT_GE(labels.count(l), 1u) << l << " not found: " << r.out;
	EXPECT_GE(labels.count("door"), 1u);
}

TEST_F(SemnavMapCli, NoCascadesDetectsNoObjects)
{
	const AppRun r = mapWith("--no-cascades");
	ASSERT_EQ(r.code, 0) << r.err;
	const auto labels = objectLabels(r.out);
	for (const auto& l : kDetected) EXPECT_EQ(labels.count(l), 0u) << l;
	EXPECT_GE(labels.count("door"), 1u);  // the rules still find doors
	const AppRun both = mapWith("--no-cascades --cascades x.ini");
	EXPECT_EQ(both.code, 2);
	EXPECT_EQ(lineCount(both.err), 1u) << both.err;
}

TEST_F(SemnavMapCli, BadCascadeFilesAreOneLineNamingTheFile)
{
	// A cascade XML cut in half, a shape model of garbage, a missing
	// cascade, a missing detector INI file.
	const fs::path cut = kMapCliTmp / "cut-washbasin.xml";
	{
		std::ifstream in(test::kSourceDir + "/datasets/cascades/washbasin.xml");
		std::string text((std::istreambuf_iterator<char>(in)), {});
		std::ofstream(cut) << text.substr(0, text.size() / 2);
	}
	const fs::path garbage = kMapCliTmp / "garbage-shape.xml.gz";
	std::ofstream(garbage) << "not a forest";
	const fs::path missing = kMapCliTmp / "missing.xml";
	const std::pair<fs::path, fs::path> cases[] = {
	    {cascadeIniNaming("cascade", cut, "cut.ini"), cut},
	    {cascadeIniNaming("shape_model", garbage, "garbage.ini"), garbage},
	    {cascadeIniNaming("cascade", missing, "missing.ini"), missing},
	    {kMapCliTmp / "no-such.ini", kMapCliTmp / "no-such.ini"}};
	for (const auto& [ini, named] : cases)
	{
		const AppRun r = mapWith("--cascades " + ini.string());
		EXPECT_EQ(r.code, 1) << ini;
		EXPECT_EQ(lineCount(r.err), 1u) << ini << ": " << r.err;
		EXPECT_NE(r.err.find(named.filename().string()), std::string::npos)
		    << r.err;
		EXPECT_EQ(r.err.rfind("semnav-map: ", 0), 0u) << r.err;
		EXPECT_TRUE(r.out.empty()) << r.out;
	}
	// Without --cascades the detector INI file is $SEMNAV_CONFIG_DIR's.
	const fs::path dir = kMapCliTmp / "config-dir";
	fs::create_directories(dir);
	fs::copy_file(
	    cascadeIniNaming("cascade", cut, "cut.ini"), dir / "cascade.ini",
	    fs::copy_options::overwrite_existing);
	::setenv("SEMNAV_CONFIG_DIR", dir.c_str(), 1);
	const AppRun env = mapWith("");
	::unsetenv("SEMNAV_CONFIG_DIR");
	EXPECT_EQ(env.code, 1);
	EXPECT_EQ(lineCount(env.err), 1u) << env.err;
	EXPECT_NE(env.err.find(cut.filename().string()), std::string::npos)
	    << env.err;
}

TEST_F(SemnavMapCli, WriteConfigWritesWhatConfigLoads)
{
	const fs::path ini = kMapCliTmp / "written.ini";
	const AppRun w = runApp("semnav-map", "--write-config " + ini.string());
	ASSERT_EQ(w.code, 0) << w.err;
	EXPECT_TRUE(w.out.empty());
	std::ifstream in(ini);
	const std::string text((std::istreambuf_iterator<char>(in)), {});
	for (const char* s :
	     {"[SemanticMap]", "[TravelCost]", "[SweepAssembler]", "[NormalImage]",
	      "[RuleClassifier]", "[WallExtractor]", "[Localizer]"})
		EXPECT_NE(text.find(s), std::string::npos) << s;
	// The defaults written load back and map as without --config.
	const AppRun r = mapWith("--config " + ini.string() + " --no-cascades");
	EXPECT_EQ(r.code, 0) << r.err;
	EXPECT_EQ(
	    runApp("semnav-map", "--write-config /nonexistent-dir/x.ini").code, 1);
}

TEST_F(SemnavMapCli, ThreeDtkScanWithoutPoseIsRefusedNamingTheFile)
{
	// Two scan lines of a wall 3 m ahead; no scan.pose beside them.
	const fs::path scan = kMapCliTmp / "scan.3d";
	{
		std::ofstream f(scan);
		for (int row = 0; row < 2; row++)
			for (int c = 0; c < 360; c++)
				f << (c - 180) * 0.5 << " " << row * 2.0 << " 300\n";
	}
	const AppRun r = runApp(
	    "semnav-map", "--no-cascades --3dtk " + scan.string() + " --out " +
	                      (kMapCliTmp / "map3dtk").string());
	EXPECT_EQ(r.code, 1) << r.err;
	EXPECT_EQ(lineCount(r.err), 1u) << r.err;
	EXPECT_NE(
	    r.err.find("no pose file " + (kMapCliTmp / "scan.pose").string()),
	    std::string::npos)
	    << r.err;
	EXPECT_FALSE(fs::exists(kMapCliTmp / "map3dtk" / "map.yaml"));
}
