/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/common/CommandLine.h>

#include <optional>
#include <string>

namespace semnav
{
/** The object-detection arguments of the apps that perceive: the paper's
 * whole pipeline (rules, Haar cascades, 3D checks) is the default, with
 * the shipped config/cascade.ini (see ShippedConfig); `--cascades FILE`
 * names another detector INI file, `--no-cascades` turns object detection
 * off (rules only). Giving both is bad usage. */
class CascadeArgs
{
public:
	/** Adds the two arguments to `cli` and the check that not both are
	 * given. */
	explicit CascadeArgs(CommandLine& cli);

	/** The detector INI file to use; nothing with --no-cascades. */
	std::optional<std::string> file() const;

private:
	// mutable: TCLAP's getValue() is not const.
	mutable TCLAP::ValueArg<std::string> m_file;
	mutable TCLAP::SwitchArg m_off;
};

}  // namespace semnav
