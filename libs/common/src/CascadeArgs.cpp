/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/CascadeArgs.h>
#include <semnav/common/ShippedConfig.h>

namespace semnav
{
CascadeArgs::CascadeArgs(CommandLine& cli)
    : m_file(
          "", "cascades",
          "Detector INI file of the washbasin, wastebasket and stairs "
          "detection (Haar cascades and 3D shape checks). Default: "
          "cascade.ini in $SEMNAV_CONFIG_DIR, else in " +
              ShippedConfig::directory(),
          false, "", "C.ini", cli.cmd()),
      m_off(
          "", "no-cascades",
          "No object detection: rule-based labels only (doors but no "
          "washbasins, wastebaskets or stairs)",
          cli.cmd(), false)
{
	cli.addCheck(
	    [this]() -> std::optional<std::string>
	    {
		    if (m_off.getValue() && !m_file.getValue().empty())
			    return "give --cascades or --no-cascades, not both";
		    return std::nullopt;
	    });
}

std::optional<std::string> CascadeArgs::file() const
{
	if (m_off.getValue()) return std::nullopt;
	if (!m_file.getValue().empty()) return m_file.getValue();
	return ShippedConfig::path("cascade.ini");
}
}  // namespace semnav
