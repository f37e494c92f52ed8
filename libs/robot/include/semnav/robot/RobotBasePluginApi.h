/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

/** \file RobotBasePluginApi.h
 * What a robot base driver plugin compiles against (headers only): a shared
 * library that makes a semnav::RobotBase, loaded by RobotBasePlugin
 * (`semnav-robot --plugin libX.so`). The plugin ends with
 *
 * \code
 * semnav::RobotBase* createMyBase(
 *     const mrpt::config::CConfigFileBase& cfg, const std::string& section)
 * {
 *     return new MyBase(cfg, section);  // may throw; keys of [section]
 * }
 * SEMNAV_ROBOT_BASE_PLUGIN("MyBase", createMyBase)
 * \endcode
 *
 * which exports, with C linkage:
 * - `int semnav_robot_base_abi()`: SEMNAV_ROBOT_BASE_ABI when it was built;
 * - `int semnav_robot_base_mrpt()`: MRPT_VERSION when it was built;
 * - `const char* semnav_robot_base_name()`: its name, which is also the INI
 *   section its options are read from ([MyBase] of robot.ini);
 * - `semnav::RobotBase* semnav_robot_base_create(const
 *   mrpt::config::CConfigFileBase&, const std::string& section)`.
 *
 * The ABI rule: a plugin is loaded only when its SEMNAV_ROBOT_BASE_ABI equals
 * the loader's and both were built against the same MRPT major.minor
 * version (MRPT changes its ABI between minor versions). The factory may
 * return a raw pointer or a std::unique_ptr; ownership passes to the loader,
 * which deletes the base (its virtual destructor, i.e. the plugin's code)
 * before it unloads the library. */

#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/version.h>
#include <semnav/robot/RobotBase.h>

#include <memory>
#include <string>

/** The version of the plugin ABI: the layout of semnav::RobotBase (its
 * virtual functions, RobotBase::Odometry) and the exported symbols. Raised
 * whenever one of them changes. */
#define SEMNAV_ROBOT_BASE_ABI 1

namespace semnav
{
/** The signature of the exported factory (semnav_robot_base_create). */
using RobotBaseFactory =
    RobotBase* (*)(const mrpt::config::CConfigFileBase&, const std::string&);

/** MRPT's version without its patch number (0x258 -> 0x250): plugin and
 * loader must agree on it. */
constexpr int mrptAbiVersion(int mrptVersion)
{
	return mrptVersion & ~0xF;
}

}  // namespace semnav

/** Exports the plugin's entry points (see the file's comment). `Name`: a
 * string literal naming the base and its INI section; `FactoryFn`: a
 * function (cfg, section) returning a new base as RobotBase* or
 * std::unique_ptr. Used once, at namespace scope, in one .cpp file. */
#define SEMNAV_ROBOT_BASE_PLUGIN(Name, FactoryFn)                             \
	extern "C" __attribute__((visibility("default"))) int                     \
	semnav_robot_base_abi()                                                   \
	{                                                                         \
		return SEMNAV_ROBOT_BASE_ABI;                                         \
	}                                                                         \
	extern "C" __attribute__((visibility("default"))) int                     \
	semnav_robot_base_mrpt()                                                  \
	{                                                                         \
		return MRPT_VERSION;                                                  \
	}                                                                         \
	extern "C" __attribute__((visibility("default"))) const char*             \
	semnav_robot_base_name()                                                  \
	{                                                                         \
		return Name;                                                          \
	}                                                                         \
	extern "C" __attribute__((visibility("default"))) semnav::RobotBase*      \
	semnav_robot_base_create(                                                 \
	    const mrpt::config::CConfigFileBase& cfg, const std::string& section) \
	{                                                                         \
		return std::unique_ptr<semnav::RobotBase>(FactoryFn(cfg, section))    \
		    .release();                                                       \
	}
