/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/ShippedConfig.h>

#include <cstdlib>
#include <filesystem>

namespace semnav
{
std::string ShippedConfig::directory()
{
	const char* env = std::getenv(kEnvironmentVariable);
	if (env && *env) return env;
	return SEMNAV_CONFIG_DIR;
}

std::string ShippedConfig::path(const std::string& name)
{
	return (std::filesystem::path(directory()) / name).string();
}
}  // namespace semnav
