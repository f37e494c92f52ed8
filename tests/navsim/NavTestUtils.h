/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once
// The shipped navigation configuration and scenes of the source tree, for
// the navigation tests.
#include <semnav/navsim/SimulationConfig.h>
#include <semnav/sim/SceneLoader.h>

#include <string>

namespace semnav::test
{
inline const std::string& sourceDir()
{
	static const std::string s = SEMNAV_SOURCE_DIR;
	return s;
}

/** config/navigation.ini + config/planning.ini, loaded once. */
inline const SimulationConfig& shippedNavigationConfig()
{
	static const SimulationConfig c = SimulationConfig::load(
	    sourceDir() + "/config/navigation.ini",
	    sourceDir() + "/config/planning.ini", sourceDir() + "/config/sim.ini");
	return c;
}

/** A scene file of the source tree (path relative to it). */
inline Scene sourceScene(const std::string& relativePath)
{
	return SceneLoader::loadFile(sourceDir() + "/" + relativePath);
}

}  // namespace semnav::test
