/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CConfigFileBase.h>
#include <semnav/robot/RobotBase.h>
#include <semnav/robot/RobotBasePluginApi.h>

#include <memory>
#include <string>

namespace semnav
{
/** A robot base driver from a shared library (`semnav-robot --plugin
 * libX.so`, as MRPT's `rawlog-grabber -p` loads sensors); the library is
 * written with RobotBasePluginApi.h.
 *
 * \code
 * RobotBasePlugin plugin("./libmy_base.so");      // load and check
 * std::shared_ptr<RobotBase> base = plugin.create(robotIni);  // [MyBase]
 * \endcode
 *
 * Loading: dlopen(RTLD_NOW | RTLD_LOCAL) (a name without '/' is searched as
 * dlopen does), then the plugin's ABI and MRPT version are checked against
 * this build's (RobotBasePluginApi.h: the ABI rule). Errors are one line
 * naming the file: IoError when the file is missing or cannot be loaded,
 * Error when it is no semnav robot base plugin or was built for another
 * ABI or MRPT.
 *
 * The library stays loaded while this object or any base it made lives:
 * a base is destroyed before its library is unloaded. */
class RobotBasePlugin
{
public:
	/** Loads and checks `path`; throws as said above. */
	explicit RobotBasePlugin(const std::string& path);

	/** The file as given. */
	const std::string& path() const { return m_path; }
	/** The plugin's name (semnav_robot_base_name), also its INI section. */
	const std::string& name() const { return m_name; }

	/** A new base from [name()] of `cfg`. Exceptions of the plugin's
	 * factory are rethrown as one line naming the file: ConfigError for
	 * ConfigError (a bad key), Error otherwise; a null base is an Error. */
	std::shared_ptr<RobotBase> create(
	    const mrpt::config::CConfigFileBase& cfg) const
	{
		return create(cfg, m_name);
	}
	/** As create(cfg), from [section]. */
	std::shared_ptr<RobotBase> create(
	    const mrpt::config::CConfigFileBase& cfg,
	    const std::string& section) const;

private:
	/** The exported symbol `symbol`, or Error naming it. */
	void* lookUp(const char* symbol) const;
	void checkVersions() const;

	std::string m_path;
	std::string m_name;
	/** The dlopen handle; dlclose when the last owner goes. */
	std::shared_ptr<void> m_library;
	RobotBaseFactory m_factory = nullptr;
};

}  // namespace semnav
