/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CLoadableOptions.h>

#include <string>
#include <vector>

namespace semnav
{
/** One INI section and the options saved into it (their
 * saveToConfigFile() may add sections of their own, e.g.
 * [CascadeDetector.stairs]). */
struct ConfigSection
{
	std::string name;
	const mrpt::config::CLoadableOptions* options = nullptr;
};

/** The INI text of `sections`, as the shipped config files are written:
 * `header` as "# " lines, then per section "[name]" and every key its
 * saveToConfigFile() writes, in order, each below its one-line doc as a
 * "# " comment. */
std::string configText(
    const std::vector<ConfigSection>& sections, const std::string& header = "");

/** Writes configText() to `path` (atomically); throws IoError. E.g.
 * `writeConfigFile(path, {{"SemanticMap", &mapOptions}, {"TravelCost",
 * &mapOptions.cost}})` for an app's `--write-config FILE`. */
void writeConfigFile(
    const std::string& path, const std::vector<ConfigSection>& sections,
    const std::string& header = "");

}  // namespace semnav
