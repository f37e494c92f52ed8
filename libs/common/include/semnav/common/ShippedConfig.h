/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <string>

namespace semnav
{
/** Where the apps find the shipped configuration (the INI files of config/,
 * which in turn name the models under datasets/cascades/) without flags: the
 * directory named by the environment variable SEMNAV_CONFIG_DIR when it is
 * set and not empty, else the source tree's config/ compiled in by CMake.
 * A flag naming a file (e.g. --cascades FILE) always wins. */
class ShippedConfig
{
public:
	/** The environment variable that overrides the compiled-in directory. */
	static constexpr const char* kEnvironmentVariable = "SEMNAV_CONFIG_DIR";

	/** $SEMNAV_CONFIG_DIR, else the compiled-in config directory. */
	static std::string directory();
	/** directory()/name, e.g. path("cascade.ini"). */
	static std::string path(const std::string& name);
};

}  // namespace semnav
