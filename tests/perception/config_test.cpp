/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <semnav/common/ConfigChecks.h>
#include <semnav/common/Error.h>
#include <semnav/perception/PerceptionPipeline.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

using namespace semnav;

namespace
{
const std::string kIni =
    std::string(SEMNAV_SOURCE_DIR) + "/config/perception.ini";

/** All keys of all sections as one comparable text. */
std::string dump(const mrpt::config::CConfigFileBase& c)
{
	std::string out;
	std::vector<std::string> sections;
	c.getAllSections(sections);
	std::sort(sections.begin(), sections.end());
	for (const auto& s : sections)
	{
		std::vector<std::string> keys;
		c.getAllKeys(s, keys);
		std::sort(keys.begin(), keys.end());
		for (const auto& k : keys)
		{
			// Numbers compared as numbers (the INI may write 5 for 5.0).
			const std::string v = c.read_string(s, k, "");
			try
			{
				std::size_t used = 0;
				const double d = std::stod(v, &used);
				if (used == v.size())
				{
					out += s + "." + k + "=" + std::to_string(d) + "\n";
					continue;
				}
			}
			catch (const std::exception&)
			{
			}
			out += s + "." + k + "=" + v + "\n";
		}
	}
	return out;
}
}  // namespace

TEST(PerceptionConfig, ShippedIniLoadsAndEqualsTheDefaults)
{
	const auto cfg = openIniFile(kIni, PerceptionPipeline::sections());
	PerceptionPipeline::TOptions loaded;
	ASSERT_NO_THROW(loaded.loadFromConfigFile(*cfg, ""));
	// Every section present, every key known (checked by the load) and the
	// values are the built-in defaults (so the app without --config and
	// with the shipped file behave the same).
	for (const auto& s : PerceptionPipeline::sections())
		EXPECT_TRUE(cfg->sectionExists(s)) << s;
	mrpt::config::CConfigFileMemory a, b;
	loaded.saveToConfigFile(a, "");
	PerceptionPipeline::TOptions().saveToConfigFile(b, "");
	EXPECT_EQ(dump(a), dump(b));
	// And the file sets every key the options have.
	mrpt::config::CConfigFileMemory shipped;
	for (const auto& s : PerceptionPipeline::sections())
	{
		std::vector<std::string> keys;
		b.getAllKeys(s, keys);
		for (const auto& k : keys)
			EXPECT_TRUE(cfg->keyExists(s, k)) << "[" << s << "] " << k;
	}
}

TEST(PerceptionConfig, UnknownSectionsAndValuesAreErrors)
{
	const auto dir = std::filesystem::temp_directory_path() /
	                 ("semnav_pcfg_" + std::to_string(::getpid()));
	std::filesystem::create_directories(dir);
	const std::string bad = (dir / "bad.ini").string();
	{
		std::ofstream f(bad);
		f << "[RuleClasifier]\nground_tolerance_m = 0.1\n";
	}
	EXPECT_THROW(openIniFile(bad, PerceptionPipeline::sections()), ConfigError);
	{
		std::ofstream f(bad);
		f << "[Roughness]\nsquare_width_px = 0\n";
	}
	const auto cfg = openIniFile(bad, PerceptionPipeline::sections());
	PerceptionPipeline::TOptions o;
	EXPECT_THROW(o.loadFromConfigFile(*cfg, ""), ConfigError);
	std::filesystem::remove_all(dir);
}
