/* semnav: semantic navigation from tilting-laser sweeps */
// The CLI pieces the apps share: parsePose, the detection arguments and
// where the shipped config is found, --config/--write-config over
// IniSections, the median.
#include <gtest/gtest.h>
#include <semnav/common/CascadeArgs.h>
#include <semnav/common/CommandLine.h>
#include <semnav/common/Error.h>
#include <semnav/common/IniSections.h>
#include <semnav/common/Percentile.h>
#include <semnav/common/ShippedConfig.h>
#include <stdlib.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

using namespace semnav;
namespace fs = std::filesystem;

namespace
{
/** Runs CommandLine::parse on `args` (argv[0] added). */
std::optional<int> parse(CommandLine& cli, std::vector<std::string> args)
{
	args.insert(args.begin(), "app");
	std::vector<char*> argv;
	for (auto& a : args) argv.push_back(a.data());
	return cli.parse(static_cast<int>(argv.size()), argv.data());
}

/** A two-key options struct. */
struct Opts : public mrpt::config::CLoadableOptions
{
	double range = 1.5;
	int count = 3;
	void loadFromConfigFile(
	    const mrpt::config::CConfigFileBase& c, const std::string& s) override
	{
		range = c.read_double(s, "range_m", range);
		count = c.read_int(s, "count", count);
	}
	void saveToConfigFile(
	    mrpt::config::CConfigFileBase& c, const std::string& s) const override
	{
		c.write(s, "range_m", range);
		c.write(s, "count", count);
	}
};

const fs::path kTmp =
    fs::temp_directory_path() / ("semnav_cli_" + std::to_string(::getpid()));
}  // namespace

TEST(CommandLine, ParsePoseTakesDegreesAndRejectsJunk)
{
	const auto p = CommandLine::parsePose("1.5,-2,90");
	ASSERT_TRUE(p);
	EXPECT_DOUBLE_EQ(p->x, 1.5);
	EXPECT_DOUBLE_EQ(p->y, -2);
	EXPECT_NEAR(p->phi, M_PI / 2, 1e-12);
	for (const char* bad :
	     {"", "1,2", "1,2,3,4", "1,x,3", "1,2,3deg", "nan,0,0"})
		EXPECT_FALSE(CommandLine::parsePose(bad)) << bad;
}

TEST(CommandLine, ParseNumbersWantsExactlyThatManyFiniteNumbers)
{
	const auto v = CommandLine::parseNumbers("0.1,-2,0.45", 3);
	ASSERT_TRUE(v);
	EXPECT_EQ(*v, (std::vector<double>{0.1, -2, 0.45}));
	for (const char* bad : {"", "1,2", "1,2,3,4", "1,,3", "1,2,3m", "0,inf,0"})
		EXPECT_FALSE(CommandLine::parseNumbers(bad, 3)) << bad;
}

TEST(CommandLine, MedianOfEvenCountIsTheMeanOfTheMiddleTwo)
{
	EXPECT_EQ(median({}), 0.0);
	EXPECT_EQ(median({3, 1, 2}), 2.0);
	EXPECT_EQ(median({4, 1, 3, 2}), 2.5);
}

TEST(CascadeArgs, ShippedFileByDefaultOverridableAndOff)
{
	::unsetenv(ShippedConfig::kEnvironmentVariable);
	{
		CommandLine cli("app", "test");
		CascadeArgs c(cli);
		ASSERT_FALSE(parse(cli, {}));
		ASSERT_TRUE(c.file());
		EXPECT_EQ(*c.file(), ShippedConfig::path("cascade.ini"));
		EXPECT_TRUE(fs::exists(*c.file())) << *c.file();
	}
	{
		::setenv(ShippedConfig::kEnvironmentVariable, "/elsewhere", 1);
		CommandLine cli("app", "test");
		CascadeArgs c(cli);
		ASSERT_FALSE(parse(cli, {}));
		EXPECT_EQ(*c.file(), "/elsewhere/cascade.ini");
		::unsetenv(ShippedConfig::kEnvironmentVariable);
	}
	{
		CommandLine cli("app", "test");
		CascadeArgs c(cli);
		ASSERT_FALSE(parse(cli, {"--cascades", "mine.ini"}));
		EXPECT_EQ(*c.file(), "mine.ini");
	}
	{
		CommandLine cli("app", "test");
		CascadeArgs c(cli);
		ASSERT_FALSE(parse(cli, {"--no-cascades"}));
		EXPECT_FALSE(c.file());
	}
	CommandLine cli("app", "test");
	CascadeArgs c(cli);
	EXPECT_EQ(parse(cli, {"--no-cascades", "--cascades", "x.ini"}), 2);
}

TEST(IniSections, WriteConfigWritesDefaultsThatConfigLoads)
{
	fs::create_directories(kTmp);
	const fs::path ini = kTmp / "defaults.ini";
	Opts a, b;
	IniSections sections;
	sections.add(a, "A").add(b, "B");
	EXPECT_EQ(sections.sections(), (std::vector<std::string>{"A", "B"}));
	{
		CommandLine cli("app", "test");
		cli.addConfig(sections, "INI file");
		EXPECT_EQ(parse(cli, {"--write-config", ini.string()}), 0);
	}
	// Changed values, then the written defaults loaded back.
	a.range = 9;
	b.count = 7;
	sections.load(ini.string());
	EXPECT_EQ(a.range, 1.5);
	EXPECT_EQ(b.count, 3);
	// An unknown section is an error naming the file.
	std::ofstream(kTmp / "bad.ini") << "[C]\nx = 1\n";
	try
	{
		sections.load((kTmp / "bad.ini").string());
		FAIL() << "no error";
	}
	catch (const ConfigError& e)
	{
		EXPECT_NE(std::string(e.what()).find("bad.ini"), std::string::npos)
		    << e.what();
	}
	// An unwritable file: exit 1.
	CommandLine cli("app", "test");
	cli.addConfig(sections, "INI file");
	EXPECT_EQ(parse(cli, {"--write-config", "/nonexistent-dir/x.ini"}), 1);
	fs::remove_all(kTmp);
}
