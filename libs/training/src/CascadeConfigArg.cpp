/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/training/CascadeConfigArg.h>

namespace semnav
{
CascadeConfigArg::CascadeConfigArg(CommandLine& cli, bool required)
    : m_sections(m_defaults.iniSections()),
      m_arg(
          "", "config",
          std::string("Detector INI file (see config/cascade.ini)") +
              (required ? "; required" : "; default: built-in values"),
          false, "", "C.ini", cli.cmd())
{
	cli.addWriteConfig(m_sections);
	if (required)
		cli.addCheck(
		    [this]() -> std::optional<std::string>
		    {
			    if (path().empty()) return "missing --config";
			    return std::nullopt;
		    });
}
}  // namespace semnav
