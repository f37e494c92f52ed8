/* semnav: semantic navigation from tilting-laser sweeps */
// libFuzzer harness: INI text through openIniFile() (as the apps read
// their configs), then through the loadFromConfigFile() of the
// options structs of the reading and mapping libraries (scan, perception,
// map, cascade, robot, sim), each loaded from every section the text has.
// Seeds: config/*.ini, copied by scripts/fuzz.
#include <mrpt/config/CConfigFile.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <semnav/cascade/CascadeTrainer.h>
#include <semnav/common/ConfigChecks.h>
#include <semnav/common/Error.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/map/TravelCostModel.h>
#include <semnav/perception/PerceptionPipeline.h>
#include <semnav/robot/SweepObstacles.h>
#include <semnav/scan/SweepAssembler.h>
#include <semnav/scan/ThreeDtkReader.h>
#include <semnav/sim/SimulatedRobotOptions.h>
#include <semnav/sim/SimulatorOptions.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "FuzzFiles.h"

using namespace semnav;

namespace
{
using Make = std::function<std::unique_ptr<mrpt::config::CLoadableOptions>()>;

template <class T>
Make make()
{
	return [] { return std::make_unique<T>(); };
}

const std::vector<Make>& optionStructs()
{
	static const std::vector<Make> all = {
	    make<SweepAssembler::TOptions>(),     make<ThreeDtkReader::TOptions>(),
	    make<NormalImage::TOptions>(),        make<Roughness::TOptions>(),
	    make<RangeSegmentation::TOptions>(),  make<RuleClassifier::TOptions>(),
	    make<PerceptionPipeline::TOptions>(), make<SemanticMap::TOptions>(),
	    make<TravelCostModel::TOptions>(),    make<CascadeTrainer::TOptions>(),
	    make<SweepObstacles::TOptions>(),     make<SimulatorOptions>(),
	    make<SimulatedRobotOptions>()};
	return all;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
	// As the apps open a file: MRPT's parser errors must be ConfigError
	// (with no known section, a file with sections is one too).
	static const auto path = fuzz::scratchDir("ini") / "input.ini";
	fuzz::writeBytes(path, data, size);
	try
	{
		openIniFile(path.string(), {});
	}
	catch (const ConfigError&)
	{
	}
	std::unique_ptr<mrpt::config::CConfigFileMemory> ini;
	try
	{
		ini = std::make_unique<mrpt::config::CConfigFileMemory>(
		    std::string(reinterpret_cast<const char*>(data), size));
	}
	catch (const std::exception&)
	{
		return 0;  // the parse error openIniFile has just named
	}
	std::vector<std::string> sections;
	ini->getAllSections(sections);
	for (const auto& section : sections)
		for (const auto& makeOptions : optionStructs())
		{
			try
			{
				makeOptions()->loadFromConfigFile(*ini, section);
			}
			catch (const Error&)
			{
			}
		}
	return 0;
}
