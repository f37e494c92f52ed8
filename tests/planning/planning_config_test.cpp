/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <semnav/common/ConfigChecks.h>
#include <semnav/common/Error.h>
#include <semnav/planning/CnnPlanner.h>
#include <semnav/planning/TraversabilityBuilder.h>

using namespace semnav;

namespace
{
const std::string kIni =
    std::string(SEMNAV_SOURCE_DIR) + "/config/planning.ini";

void expectSame(
    const TraversabilityBuilder::TOptions& a,
    const TraversabilityBuilder::TOptions& b)
{
	EXPECT_EQ(a.L, b.L);
	EXPECT_EQ(a.robotType, b.robotType);
	EXPECT_EQ(a.robotRadius, b.robotRadius);
	EXPECT_EQ(a.profile, b.profile);
	EXPECT_EQ(a.shortestRadius, b.shortestRadius);
	EXPECT_EQ(a.safeRadius, b.safeRadius);
	EXPECT_EQ(a.safeRingCost, b.safeRingCost);
	EXPECT_EQ(a.uUnobserved, b.uUnobserved);
	EXPECT_EQ(a.goalReach, b.goalReach);
	EXPECT_EQ(a.labelU, b.labelU);
	EXPECT_EQ(a.labelRadiusScale, b.labelRadiusScale);
}

std::string loadError(const std::string& ini)
{
	mrpt::config::CConfigFileMemory c(ini);
	try
	{
		TraversabilityBuilder::TOptions t;
		t.loadFromConfigFile(c, "Traversability");
		CnnPlanner::TOptions p;
		p.loadFromConfigFile(c, "CnnPlanner");
	}
	catch (const ConfigError& e)
	{
		return e.what();
	}
	return "";
}
}  // namespace

TEST(PlanningConfig, ShippedFileHoldsEveryKeyAtItsDefault)
{
	const auto cfg = openIniFile(kIni, {"CnnPlanner", "Traversability"});
	for (const auto& [section, keys] :
	     {std::make_pair(
	          std::string("CnnPlanner"), CnnPlanner::TOptions::knownKeys()),
	      std::make_pair(
	          std::string("Traversability"),
	          TraversabilityBuilder::TOptions::knownKeys())})
	{
		std::vector<std::string> present;
		cfg->getAllKeys(section, present);
		EXPECT_EQ(present.size(), keys.size()) << section;
		for (const auto& k : keys)
			EXPECT_NE(cfg->read_string(section, k, "", false), "")
			    << "[" << section << "] " << k << " missing";
	}
	CnnPlanner::TOptions p;
	p.schedule = CnnSchedule::Jacobi;
	p.threads = 7;
	p.maxIterations = 9;
	p.loadFromConfigFile(*cfg, "CnnPlanner");
	const CnnPlanner::TOptions pd;
	EXPECT_EQ(p.schedule, pd.schedule);
	EXPECT_EQ(p.threads, pd.threads);
	EXPECT_EQ(p.maxIterations, pd.maxIterations);

	TraversabilityBuilder::TOptions t;
	t.robotRadius = 1;
	t.robotType = RobotType::Walking;
	t.labelU[static_cast<int>(Label::Grass)] = 3;
	t.loadFromConfigFile(*cfg, "Traversability");
	expectSame(t, TraversabilityBuilder::TOptions());
}

TEST(PlanningConfig, ValuesWordsAndRoundTrip)
{
	mrpt::config::CConfigFileMemory c(
	    "[Traversability]\nL = 500\nrobot_type = walking\nprofile = safe\n"
	    "u_floor = blocked\nu_grass = 2.5\nr_scale_stairs = 2\n"
	    "[CnnPlanner]\nschedule = jacobi\nthreads = 2\n");
	TraversabilityBuilder::TOptions t;
	t.loadFromConfigFile(c, "Traversability");
	EXPECT_EQ(t.L, 500);
	EXPECT_EQ(t.robotType, RobotType::Walking);
	EXPECT_EQ(t.profile, CostProfile::Safe);
	const double blocked = TraversabilityBuilder::kBlocked;
	EXPECT_EQ(t.labelU[static_cast<int>(Label::Floor)], blocked);
	EXPECT_EQ(t.labelU[static_cast<int>(Label::Wall)], blocked);
	EXPECT_EQ(TraversabilityBuilder(t).labelCost(Label::Floor), 500);
	EXPECT_EQ(t.labelU[static_cast<int>(Label::Grass)], 2.5);
	EXPECT_EQ(t.labelRadiusScale[static_cast<int>(Label::Stairs)], 2);
	EXPECT_EQ(t.uUnobserved, blocked);
	CnnPlanner::TOptions p;
	p.loadFromConfigFile(c, "CnnPlanner");
	EXPECT_EQ(p.schedule, CnnSchedule::Jacobi);
	EXPECT_EQ(p.threads, 2);

	mrpt::config::CConfigFileMemory out;
	t.saveToConfigFile(out, "Traversability");
	p.saveToConfigFile(out, "CnnPlanner");
	TraversabilityBuilder::TOptions t2;
	t2.loadFromConfigFile(out, "Traversability");
	expectSame(t2, t);
	CnnPlanner::TOptions p2;
	p2.loadFromConfigFile(out, "CnnPlanner");
	EXPECT_EQ(p2.schedule, p.schedule);
	EXPECT_EQ(p2.threads, p.threads);
}

TEST(PlanningConfig, BadKeysAndValuesAreConfigErrors)
{
	const auto has = [](const std::string& m, const char* w)
	{ return m.find(w) != std::string::npos; };
	EXPECT_TRUE(has(
	    loadError("[Traversability]\nrobot_radius = 0.3\n"), "unknown key"));
	EXPECT_TRUE(has(loadError("[CnnPlanner]\nthread = 2\n"), "unknown key"));
	EXPECT_TRUE(has(
	    loadError("[Traversability]\nrobot_radius_m = 7\n"), "out of range"));
	EXPECT_TRUE(
	    has(loadError("[Traversability]\nu_grass = -1\n"), "out of range"));
	EXPECT_TRUE(
	    has(loadError("[Traversability]\nu_grass = lots\n"), "not a number"));
	EXPECT_TRUE(
	    has(loadError("[Traversability]\nrobot_type = flying\n"), "wheeled"));
	EXPECT_TRUE(has(loadError("[Traversability]\nprofile = fast\n"), "safe"));
	EXPECT_TRUE(has(loadError("[CnnPlanner]\nschedule = async\n"), "jacobi"));
	EXPECT_TRUE(
	    has(loadError("[CnnPlanner]\nmax_iterations = 2.5\n"), "integer"));
	EXPECT_EQ(loadError("[Traversability]\nu_wall = Blocked\n"), "");
	// A number equal to L blocks too; a smaller L makes big costs block.
	mrpt::config::CConfigFileMemory c2(
	    "[Traversability]\nL = 10\nu_grass = 10\nu_door = 3\n");
	TraversabilityBuilder::TOptions t2;
	t2.loadFromConfigFile(c2, "Traversability");
	EXPECT_EQ(
	    t2.labelU[static_cast<int>(Label::Grass)],
	    TraversabilityBuilder::kBlocked);
	EXPECT_EQ(t2.labelU[static_cast<int>(Label::Door)], 3);
	// A failed load leaves the options untouched.
	mrpt::config::CConfigFileMemory c(
	    "[Traversability]\nrobot_radius_m = 0.4\nL = 0\n");
	TraversabilityBuilder::TOptions t;
	EXPECT_THROW(t.loadFromConfigFile(c, "Traversability"), ConfigError);
	EXPECT_EQ(t.robotRadius, TraversabilityBuilder::TOptions().robotRadius);
}
