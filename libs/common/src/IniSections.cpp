/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/config/CConfigFile.h>
#include <semnav/common/ConfigChecks.h>
#include <semnav/common/ConfigFileWriter.h>
#include <semnav/common/IniSections.h>

#include <algorithm>

namespace semnav
{
IniSections& IniSections::add(
    mrpt::config::CLoadableOptions& options, const std::string& section,
    const std::vector<std::string>& known)
{
	m_entries.push_back({&options, section});
	std::vector<std::string> names = known;
	if (names.empty()) names.push_back(section);
	for (const auto& n : names)
		if (std::find(m_known.begin(), m_known.end(), n) == m_known.end())
			m_known.push_back(n);
	return *this;
}

void IniSections::load(const std::string& path) const
{
	const auto cfg = openIniFile(path, m_known);
	for (const auto& e : m_entries)
		e.options->loadFromConfigFile(*cfg, e.section);
}

void IniSections::loadIfGiven(const std::string& path) const
{
	if (!path.empty()) load(path);
}

std::vector<ConfigSection> IniSections::configSections() const
{
	std::vector<ConfigSection> out;
	for (const auto& e : m_entries) out.push_back({e.section, e.options});
	return out;
}

void IniSections::write(const std::string& path) const
{
	writeConfigFile(path, configSections());
}
}  // namespace semnav
