/* semnav: semantic navigation from tilting-laser sweeps */
#include <dlfcn.h>
#include <semnav/common/Error.h>
#include <semnav/robot/RobotBasePlugin.h>

#include <cstdio>
#include <filesystem>

namespace semnav
{
namespace
{
/** dlerror() as one line, without the file name it starts with. */
std::string loaderMessage(const std::string& path)
{
	const char* e = dlerror();
	std::string m = e ? e : "unknown dlopen error";
	if (m.rfind(path + ": ", 0) == 0) m.erase(0, path.size() + 2);
	for (char& c : m)
		if (c == '\n' || c == '\r') c = ' ';
	return m;
}

std::string mrptText(int version)
{
	char text[16];
	std::snprintf(
	    text, sizeof(text), "%d.%d", (version >> 8) & 0xF,
	    (version >> 4) & 0xF);
	return text;
}
}  // namespace

RobotBasePlugin::RobotBasePlugin(const std::string& path) : m_path(path)
{
	const std::string what = "robot base plugin " + path + ": ";
	if (path.find('/') != std::string::npos && !std::filesystem::exists(path))
		throw IoError(what + "no such file");
	void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
	if (!handle) throw IoError(what + "cannot load: " + loaderMessage(path));
	m_library.reset(handle, [](void* h) { dlclose(h); });
	checkVersions();
	const auto name =
	    reinterpret_cast<const char* (*)()>(lookUp("semnav_robot_base_name"))();
	if (!name || !*name)
		throw Error(what + "semnav_robot_base_name() is empty");
	m_name = name;
	m_factory =
	    reinterpret_cast<RobotBaseFactory>(lookUp("semnav_robot_base_create"));
}

void* RobotBasePlugin::lookUp(const char* symbol) const
{
	dlerror();
	void* found = dlsym(m_library.get(), symbol);
	if (!found)
		throw Error(
		    "robot base plugin " + m_path +
		    ": not a semnav robot base plugin (no symbol " + symbol +
		    "; see SEMNAV_ROBOT_BASE_PLUGIN in semnav/robot/"
		    "RobotBasePluginApi.h)");
	return found;
}

void RobotBasePlugin::checkVersions() const
{
	const std::string what = "robot base plugin " + m_path + ": ";
	const int abi =
	    reinterpret_cast<int (*)()>(lookUp("semnav_robot_base_abi"))();
	if (abi != SEMNAV_ROBOT_BASE_ABI)
		throw Error(
		    what + "plugin ABI " + std::to_string(abi) +
		    ", this semnav needs " + std::to_string(SEMNAV_ROBOT_BASE_ABI) +
		    " (rebuild the plugin against this semnav)");
	const int mrpt =
	    reinterpret_cast<int (*)()>(lookUp("semnav_robot_base_mrpt"))();
	if (mrptAbiVersion(mrpt) != mrptAbiVersion(MRPT_VERSION))
		throw Error(
		    what + "built against MRPT " + mrptText(mrpt) +
		    ", this semnav uses MRPT " + mrptText(MRPT_VERSION) +
		    " (rebuild the plugin)");
}

std::shared_ptr<RobotBase> RobotBasePlugin::create(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section) const
{
	const std::string what = "robot base plugin " + m_path + ": ";
	const std::string making = what + "making [" + section + "]: ";
	RobotBase* base = nullptr;
	try
	{
		base = m_factory(cfg, section);
	}
	catch (const ConfigError& e)
	{
		throw ConfigError(what + e.what());
	}
	catch (const std::exception& e)
	{
		throw Error(making + e.what());
	}
	catch (...)
	{
		throw Error(making + "the factory threw a non-standard exception");
	}
	if (!base) throw Error(making + "the factory returned no base");
	// The deleter holds the library: the base goes first, then dlclose.
	return std::shared_ptr<RobotBase>(
	    base, [library = m_library](RobotBase* b) { delete b; });
}

}  // namespace semnav
