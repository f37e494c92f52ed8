/* semnav: semantic navigation from tilting-laser sweeps */
// Every file in config/ loads into the structs of its sections and equals
// what the code's defaults plus its listed overrides give (key by key).
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "ShippedConfigs.h"

using namespace semnav::test;

namespace
{
const std::string kDir = std::string(SEMNAV_SOURCE_DIR) + "/config";

std::string readText(const std::string& path)
{
	std::ifstream in(path);
	std::stringstream s;
	s << in.rdbuf();
	return s.str();
}

std::set<std::string> shippedFiles()
{
	std::set<std::string> files;
	for (const auto& e : std::filesystem::directory_iterator(kDir))
		if (e.is_regular_file() && e.path().extension() == ".ini")
			files.insert(e.path().filename().string());
	return files;
}

bool asNumber(const std::string& t, double& v)
{
	std::size_t used = 0;
	try
	{
		v = std::stod(t, &used);
	}
	catch (const std::exception&)
	{
		return false;
	}
	return used == t.size();
}

bool sameValue(const std::string& a, const std::string& b)
{
	double x = 0, y = 0;
	if (asNumber(a, x) && asNumber(b, y))
		return x == y || std::abs(x - y) <= 1e-9 * std::max(1.0, std::abs(x));
	return a == b;
}

std::vector<std::string> sections(const mrpt::config::CConfigFileBase& c)
{
	std::vector<std::string> s;
	c.getAllSections(s);
	s.erase(
	    std::remove(s.begin(), s.end(), std::string()), s.end());  // @define
	std::sort(s.begin(), s.end());
	return s;
}
}  // namespace

TEST(ShippedConfig, EveryFileInConfigHasASpec)
{
	std::set<std::string> specified;
	for (const auto& spec : shippedConfigs()) specified.insert(spec.file);
	for (const auto& f : shippedFiles())
		EXPECT_TRUE(specified.count(f))
		    << "config/" << f
		    << " is not described in tests/config/ShippedConfigs.cpp";
	for (const auto& f : specified)
		EXPECT_TRUE(shippedFiles().count(f)) << "config/" << f << " missing";
}

TEST(ShippedConfig, EachFileLoadsIntoItsSections)
{
	for (const auto& spec : shippedConfigs())
	{
		mrpt::config::CConfigFile cfg(kDir + "/" + spec.file);
		for (const auto& s : spec.sections)
		{
			auto options = s.make();
			EXPECT_NO_THROW(options->loadFromConfigFile(cfg, s.name))
			    << spec.file << " [" << s.name << "]";
		}
	}
}

TEST(ShippedConfig, EachFileIsDefaultsPlusOverrides)
{
	for (const auto& spec : shippedConfigs())
	{
		const std::string path = kDir + "/" + spec.file;
		const std::string current = readText(path);
		mrpt::config::CConfigFileMemory file(current);
		mrpt::config::CConfigFileMemory expected(expectedText(spec, current));
		EXPECT_EQ(sections(file), sections(expected)) << spec.file;
		for (const auto& s : sections(expected))
		{
			std::vector<std::string> keys, fileKeys;
			expected.getAllKeys(s, keys);
			file.getAllKeys(s, fileKeys);
			EXPECT_EQ(fileKeys, keys) << spec.file << " [" << s << "]";
			for (const auto& k : keys)
			{
				const auto want = expected.read_string(s, k, "");
				const auto got = file.read_string(s, k, "");
				EXPECT_TRUE(sameValue(got, want))
				    << spec.file << " [" << s << "] " << k << " = " << got
				    << ", defaults + overrides give " << want;
			}
		}
	}
}
