/* semnav: semantic navigation from tilting-laser sweeps */
// A plugin whose versions the build sets (PLUGIN_ABI, PLUGIN_MRPT: one
// library per wrong version) and whose factory fails: it throws what a
// driver throws when its device is absent, or, for [ReturnsNull], returns
// no base.
#include <semnav/robot/RobotBasePluginApi.h>

#include <stdexcept>

#define EXPORTED extern "C" __attribute__((visibility("default")))

EXPORTED int semnav_robot_base_abi()
{
	return PLUGIN_ABI;
}
EXPORTED int semnav_robot_base_mrpt()
{
	return PLUGIN_MRPT;
}
EXPORTED const char* semnav_robot_base_name()
{
	return "TestBase";
}
EXPORTED semnav::RobotBase* semnav_robot_base_create(
    const mrpt::config::CConfigFileBase&, const std::string& section)
{
	if (section == "ReturnsNull") return nullptr;
	throw std::runtime_error("no motor controller on /dev/ttyUSB7");
}
