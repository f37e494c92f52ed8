/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once
// The shipped localization and perception options (config/localization.ini,
// config/perception.ini) of the source tree, loaded once, for the
// navigation tests (runtime headers only: the fake-seams test uses it).
#include <mrpt/config/CConfigFile.h>
#include <semnav/common/ConfigChecks.h>
#include <semnav/localization/MappingLocalizer.h>
#include <semnav/perception/PerceptionPipeline.h>

#include <string>

namespace semnav::test
{
inline const MappingLocalizer::TOptions& shippedLocalizationOptions()
{
	static const MappingLocalizer::TOptions o = []
	{
		MappingLocalizer::TOptions t;
		t.loadFromConfigFile(
		    *openIniFile(
		        std::string(SEMNAV_SOURCE_DIR) + "/config/localization.ini",
		        MappingLocalizer::TOptions::sections()),
		    "");
		return t;
	}();
	return o;
}

inline const PerceptionPipeline::TOptions& shippedPerceptionOptions()
{
	static const PerceptionPipeline::TOptions o = []
	{
		PerceptionPipeline::TOptions t;
		t.loadFromConfigFile(
		    *openIniFile(
		        std::string(SEMNAV_SOURCE_DIR) + "/config/perception.ini",
		        PerceptionPipeline::sections()),
		    "");
		return t;
	}();
	return o;
}

}  // namespace semnav::test
