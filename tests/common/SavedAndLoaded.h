/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CConfigFileMemory.h>

#include <string>

namespace semnav::test
{
/** A TOptions round trip: `o` saved to `section` of an INI file in memory,
 * then loaded into fresh options. */
template <class Options>
Options savedAndLoaded(const Options& o, const std::string& section)
{
	mrpt::config::CConfigFileMemory mem;
	o.saveToConfigFile(mem, section);
	Options back;
	back.loadFromConfigFile(mem, section);
	return back;
}
}  // namespace semnav::test
