/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <semnav/common/ConfigFileWriter.h>
#include <semnav/common/OptionTable.h>

#include <cmath>

using namespace semnav;

namespace
{
enum class Mode
{
	Fast,
	Safe
};

struct AllKindsOpts : public mrpt::config::CLoadableOptions
{
	double lethal = 100, floor = 1, angle = 20.0 * M_PI / 180;
	int count = 3;
	bool flag = true;
	Mode mode = Mode::Fast;
	std::string path = "a.xml";
	std::vector<double> heights{0.1, 0.5};

	static const OptionTable<AllKindsOpts>& table()
	{
		static const auto t =
		    OptionTable<AllKindsOpts>()
		        .real("lethal", &AllKindsOpts::lethal, 1, 1e6, "Blocked cost.")
		        .real(
		            "floor", &AllKindsOpts::floor, 0, &AllKindsOpts::lethal,
		            "Floor cost.")
		        .angle("angle_deg", &AllKindsOpts::angle, 0, 90, "An angle.")
		        .integer("count", &AllKindsOpts::count, 1, 10, "A count.")
		        .flag("flag", &AllKindsOpts::flag, "A flag.")
		        .choice(
		            "mode", &AllKindsOpts::mode,
		            {{Mode::Fast, "fast"}, {Mode::Safe, "safe"}}, "A mode.")
		        .text("path", &AllKindsOpts::path, "A path.")
		        .reals("heights_m", &AllKindsOpts::heights, 0, 10, "Heights.")
		        .check(
		            [](const AllKindsOpts& o) { return o.count != 7; },
		            "count must not be 7");
		return t;
	}
	void loadFromConfigFile(
	    const mrpt::config::CConfigFileBase& c, const std::string& s) override
	{
		table().load(*this, c, s);
	}
	void saveToConfigFile(
	    mrpt::config::CConfigFileBase& c, const std::string& s) const override
	{
		table().save(*this, c, s);
	}
};

std::string errorOf(const std::string& ini)
{
	mrpt::config::CConfigFileMemory c(ini);
	AllKindsOpts o;
	try
	{
		o.loadFromConfigFile(c, "S");
	}
	catch (const ConfigError& e)
	{
		return e.what();
	}
	return "";
}
}  // namespace

TEST(OptionTable, LoadsEveryKindAndKeepsAbsentKeys)
{
	mrpt::config::CConfigFileMemory c(
	    "[S]\nfloor = 50\nangle_deg = 45\nmode = Safe\nheights_m = 1 2 3\n");
	AllKindsOpts o;
	o.loadFromConfigFile(c, "S");
	EXPECT_DOUBLE_EQ(o.floor, 50);
	EXPECT_DOUBLE_EQ(o.angle, M_PI / 4);
	EXPECT_EQ(o.mode, Mode::Safe);
	EXPECT_EQ(o.heights, (std::vector<double>{1, 2, 3}));
	EXPECT_EQ(o.count, 3);
	EXPECT_EQ(o.path, "a.xml");
}

TEST(OptionTable, ErrorsAsConfigChecks)
{
	EXPECT_NE(
	    errorOf("[S]\nfloo = 1\n").find("unknown key [S] floo"),
	    std::string::npos);
	EXPECT_NE(
	    errorOf("[S]\nfloor = x\n").find("not a number"), std::string::npos);
	EXPECT_NE(errorOf("[S]\ncount = 2.5\n").find("integer"), std::string::npos);
	EXPECT_NE(
	    errorOf("[S]\nflag = maybe\n").find("true/false"), std::string::npos);
	EXPECT_NE(
	    errorOf("[S]\nmode = slow\n").find("fast | safe"), std::string::npos);
	EXPECT_NE(
	    errorOf("[S]\nangle_deg = 91\n").find("out of range"),
	    std::string::npos);
	EXPECT_NE(
	    errorOf("[S]\ncount = 7\n").find("[S] count must not be 7"),
	    std::string::npos);
	EXPECT_NE(
	    errorOf("[S]\nheights_m = 1 x\n").find("heights_m"), std::string::npos);
}

TEST(OptionTable, BoundOnAnotherKeyUsesTheValueRead)
{
	EXPECT_EQ(errorOf("[S]\nlethal = 500\nfloor = 200\n"), "");
	EXPECT_NE(
	    errorOf("[S]\nlethal = 10\nfloor = 20\n").find("[S] floor"),
	    std::string::npos);
}

TEST(OptionTable, FailedLoadLeavesOptionsUnchanged)
{
	mrpt::config::CConfigFileMemory c("[S]\nfloor = 5\ncount = 99\n");
	AllKindsOpts o;
	EXPECT_THROW(o.loadFromConfigFile(c, "S"), ConfigError);
	EXPECT_DOUBLE_EQ(o.floor, 1);
}

TEST(OptionTable, SavedAndLoadedBackEqual)
{
	AllKindsOpts o;
	o.floor = 0.1 + 0.2;
	o.angle = 0.123456789;
	o.mode = Mode::Safe;
	o.heights = {0.25};
	mrpt::config::CConfigFileMemory mem;
	o.saveToConfigFile(mem, "S");
	AllKindsOpts back;
	back.floor = 7;
	back.loadFromConfigFile(mem, "S");
	EXPECT_EQ(back.floor, o.floor);
	EXPECT_NEAR(back.angle, o.angle, 1e-12);
	EXPECT_EQ(back.mode, Mode::Safe);
	EXPECT_EQ(back.heights, o.heights);
	EXPECT_EQ(AllKindsOpts::table().keys().size(), 8u);
}

TEST(OptionTable, ConfigTextHasEveryKeyBelowItsDoc)
{
	AllKindsOpts o;
	const std::string t = configText({{"S", &o}}, "Header");
	EXPECT_EQ(
	    t.rfind("# Header\n\n[S]\n# Blocked cost.\nlethal = 100\n", 0), 0u)
	    << t;
	EXPECT_NE(t.find("# An angle.\nangle_deg = 20\n"), std::string::npos) << t;
	mrpt::config::CConfigFileMemory back(t);
	AllKindsOpts loaded;
	EXPECT_NO_THROW(loaded.loadFromConfigFile(back, "S"));
}
