/* semnav: semantic navigation from tilting-laser sweeps */
// libFuzzer harness: scene YAML through SceneLoader::parse (seeds: the
// scenes in datasets/, copied by scripts/fuzz).
#include <semnav/common/Error.h>
#include <semnav/sim/SceneLoader.h>

#include <string>

using namespace semnav;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
	try
	{
		SceneLoader::parse(
		    std::string(reinterpret_cast<const char*>(data), size), "fuzz");
	}
	catch (const Error&)
	{
	}
	return 0;
}
