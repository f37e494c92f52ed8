/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/config/CConfigFile.h>
#include <mrpt/system/filesystem.h>
#include <semnav/common/CommandLine.h>
#include <semnav/common/ConfigChecks.h>
#include <semnav/common/Error.h>

#include <algorithm>
#include <cctype>
#include <sstream>

namespace semnav
{
namespace
{
std::string lower(std::string s)
{
	std::transform(
	    s.begin(), s.end(), s.begin(),
	    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
	return s;
}

std::string where(const std::string& section, const std::string& key)
{
	return "[" + section + "] " + key;
}

}  // namespace

std::string trimmed(const std::string& s)
{
	const auto b = s.find_first_not_of(" \t\r\n");
	if (b == std::string::npos) return {};
	const auto e = s.find_last_not_of(" \t\r\n");
	return s.substr(b, e - b + 1);
}

void checkKnownKeys(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section,
    const std::vector<std::string>& known)
{
	std::vector<std::string> keys;
	cfg.getAllKeys(section, keys);
	for (const auto& k : keys)
	{
		const bool ok = std::any_of(
		    known.begin(), known.end(),
		    [&](const std::string& n) { return lower(n) == lower(k); });
		if (!ok)
		{
			std::string list;
			for (const auto& n : known) list += (list.empty() ? "" : ", ") + n;
			throw ConfigError(
			    "unknown key " + where(section, k) + " (known: " + list + ")");
		}
	}
}

double readChecked(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section,
    const std::string& key, double current, double lo, double hi)
{
	const std::string text = trimmed(cfg.read_string(section, key, "", false));
	if (text.empty()) return current;
	double v = 0;
	std::size_t used = 0;
	try
	{
		v = std::stod(text, &used);
	}
	catch (const std::exception&)
	{
		used = 0;
	}
	if (used != text.size())
		throw ConfigError(
		    where(section, key) + " = '" + text + "' is not a number");
	if (!(v >= lo && v <= hi))
	{
		std::ostringstream os;
		os << where(section, key) << " = " << text << " is out of range [" << lo
		   << ", " << hi << "]";
		throw ConfigError(os.str());
	}
	return v;
}

int readCheckedInt(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section,
    const std::string& key, int current, int lo, int hi)
{
	const double v = readChecked(cfg, section, key, current, lo, hi);
	if (v != static_cast<double>(static_cast<int>(v)))
		throw ConfigError(where(section, key) + " must be an integer");
	return static_cast<int>(v);
}

bool readCheckedBool(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section,
    const std::string& key, bool current)
{
	const std::string t =
	    lower(trimmed(cfg.read_string(section, key, "", false)));
	if (t.empty()) return current;
	if (t == "true" || t == "1" || t == "yes") return true;
	if (t == "false" || t == "0" || t == "no") return false;
	throw ConfigError(where(section, key) + " = '" + t + "' is not true/false");
}

std::unique_ptr<mrpt::config::CConfigFile> openIniFile(
    const std::string& path, const std::vector<std::string>& knownSections)
{
	if (!mrpt::system::fileExists(path))
		throw ConfigError("config file not found: " + path);
	std::unique_ptr<mrpt::config::CConfigFile> cfg;
	try
	{
		cfg = std::make_unique<mrpt::config::CConfigFile>(path);
	}
	catch (const std::exception& e)
	{
		// MRPT's INI parser (an unclosed ${...}, a bad @include): one line.
		throw ConfigError(path + ": " + CommandLine::firstLine(e.what()));
	}
	std::vector<std::string> sections;
	cfg->getAllSections(sections);
	for (const auto& s : sections)
	{
		if (s.empty()) continue;
		const bool ok = std::any_of(
		    knownSections.begin(), knownSections.end(),
		    [&](const std::string& n) { return lower(n) == lower(s); });
		if (!ok)
		{
			std::string list;
			for (const auto& n : knownSections)
				list += (list.empty() ? "" : ", ") + n;
			throw ConfigError(
			    path + ": unknown section [" + s + "] (known: " + list + ")");
		}
	}
	return cfg;
}

}  // namespace semnav
