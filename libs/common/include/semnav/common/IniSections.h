/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/config/CLoadableOptions.h>
#include <semnav/common/ConfigFileWriter.h>

#include <string>
#include <vector>

namespace semnav
{
/** The INI sections an app reads, each bound to the options struct that
 * loads and saves it, declared once: the same list loads `--config FILE`
 * and writes `--write-config FILE` (the defaults, as MRPT's apps do with
 * saveToConfigFile). The options are referenced, not copied. */
class IniSections
{
public:
	/** `options` loads from and saves to `section`. Options that name their
	 * own sections (e.g. PerceptionPipeline::TOptions) take section "" and
	 * list the sections they read in `known`. */
	IniSections& add(
	    mrpt::config::CLoadableOptions& options, const std::string& section,
	    const std::vector<std::string>& known = {});

	/** Every section a file may hold. */
	const std::vector<std::string>& sections() const { return m_known; }

	/** Loads every bound options struct from the INI file `path`; throws
	 * ConfigError naming the file (missing, unknown section or key, bad
	 * value). */
	void load(const std::string& path) const;
	/** load() when `path` is not empty. */
	void loadIfGiven(const std::string& path) const;

	/** The bound sections, for configText() / writeConfigFile(). */
	std::vector<ConfigSection> configSections() const;
	/** Writes the bound options as the shipped config files are written
	 * (writeConfigFile(): each key below its doc), atomically; throws
	 * IoError. */
	void write(const std::string& path) const;

private:
	struct Entry
	{
		mrpt::config::CLoadableOptions* options;
		std::string section;
	};
	std::vector<Entry> m_entries;
	std::vector<std::string> m_known;
};

}  // namespace semnav
