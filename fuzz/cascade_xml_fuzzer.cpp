/* semnav: semantic navigation from tilting-laser sweeps */
// libFuzzer harness: cascade XML through CascadeXml::fromString. Seeds: the
// first stages of the shipped cascades (datasets/cascades), small enough to
// mutate quickly.
#include <semnav/cascade/CascadeError.h>
#include <semnav/cascade/CascadeXml.h>

#include <algorithm>
#include <string>

#include "FuzzFiles.h"

using namespace semnav;

namespace
{
/** The first `stages` stages with only the features they use. */
HaarCascade firstStagesOnly(const HaarCascade& c, std::size_t stages)
{
	HaarCascade small = c.firstStages(std::min(stages, c.stages.size()));
	small.features.clear();
	for (auto& stage : small.stages)
		for (auto& stump : stage.stumps)
		{
			small.features.push_back(c.features.at(stump.featureIdx));
			stump.featureIdx = static_cast<int>(small.features.size()) - 1;
		}
	return small;
}

void writeSeeds()
{
	if (fuzz::seedDir().empty()) return;
	const char* src = std::getenv("SEMNAV_SOURCE_DIR");
	const std::string dir =
	    std::string(src ? src : ".") + "/datasets/cascades/";
	for (const std::string name : {"wastebasket", "washbasin", "stairs"})
	{
		HaarCascade c = CascadeXml::readFile(dir + name + ".xml");
		for (const std::size_t stages : {1, 2})
		{
			fuzz::writeSeed(
			    name + "-" + std::to_string(stages) + ".xml",
			    CascadeXml::toString(firstStagesOnly(c, stages)));
		}
	}
}
}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
	writeSeeds();
	return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
	try
	{
		CascadeXml::fromString(
		    std::string(reinterpret_cast<const char*>(data), size), "fuzz");
	}
	catch (const Error&)
	{
	}
	return 0;
}
