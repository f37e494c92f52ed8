/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CConfigFileBase.h>

#include <memory>
#include <string>
#include <vector>

namespace mrpt::config
{
class CConfigFile;
}

namespace semnav
{
/** `s` without leading and trailing spaces, tabs and line ends. */
std::string trimmed(const std::string& s);

/** Throws ConfigError when `section` holds a key not listed in `known`. */
void checkKnownKeys(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section,
    const std::vector<std::string>& known);

/** Reads a number from [section] key, keeping `current` when the key is
 * absent. Throws ConfigError naming section and key when the text is not a
 * number or the value is outside [lo, hi]. */
double readChecked(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section,
    const std::string& key, double current, double lo, double hi);

/** As readChecked(), for integers. */
int readCheckedInt(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section,
    const std::string& key, int current, int lo, int hi);

/** Reads true/false/1/0/yes/no; throws ConfigError otherwise. */
bool readCheckedBool(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section,
    const std::string& key, bool current);

/** Opens an INI file; throws ConfigError when it does not exist or holds a
 * section not in `knownSections`. */
std::unique_ptr<mrpt::config::CConfigFile> openIniFile(
    const std::string& path, const std::vector<std::string>& knownSections);

}  // namespace semnav
