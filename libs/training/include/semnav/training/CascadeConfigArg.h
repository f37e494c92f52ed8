/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/common/CommandLine.h>
#include <semnav/common/IniSections.h>
#include <semnav/training/CascadeTraining.h>

#include <string>

namespace semnav
{
/** The `--config C.ini` argument of the cascade apps (semnav-detect,
 * semnav-train-cascade, semnav-train-shape): a detector and training INI
 * file such as config/cascade.ini, and `--write-config FILE` writing the
 * defaults of its sections ([CascadeDetector] and its class sections,
 * [SampleGenerator], [CascadeTrainer], [NormalImage]). */
class CascadeConfigArg
{
public:
	/** `required`: parse() reports a missing --config as bad usage. */
	CascadeConfigArg(CommandLine& cli, bool required);
	CascadeConfigArg(const CascadeConfigArg&) = delete;
	CascadeConfigArg& operator=(const CascadeConfigArg&) = delete;

	/** The file given ("" when none). */
	const std::string& path() const { return m_arg.getValue(); }

private:
	CascadeTraining::TOptions m_defaults;
	IniSections m_sections;
	// mutable: TCLAP's getValue() is not const.
	mutable TCLAP::ValueArg<std::string> m_arg;
};

}  // namespace semnav
