/* semnav: semantic navigation from tilting-laser sweeps */
// libFuzzer harness: INI text through the loadFromConfigFile() of every
// options struct of the shipped config files (tests/config), each from the
// section it is shipped in. Seeds: config/*.ini, copied by scripts/fuzz.
#include <mrpt/config/CConfigFileMemory.h>
#include <semnav/common/Error.h>

#include <string>

#include "../tests/config/ShippedConfigs.h"

using namespace semnav;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
	static const auto specs = test::shippedConfigs();
	const mrpt::config::CConfigFileMemory ini(
	    std::string(reinterpret_cast<const char*>(data), size));
	for (const auto& spec : specs)
		for (const auto& section : spec.sections)
		{
			try
			{
				section.make()->loadFromConfigFile(ini, section.name);
			}
			catch (const Error&)
			{
			}
		}
	return 0;
}
