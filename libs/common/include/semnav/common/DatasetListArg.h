/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/3rdparty/tclap/CmdLine.h>

#include <string>
#include <vector>

namespace semnav
{
/** `--datasets D1 [D2...]`: dataset directories (semnav-sim output), the
 * first after --datasets, more as the trailing unlabelled arguments. */
class DatasetListArg
{
public:
	DatasetListArg(TCLAP::CmdLine& cmd, const std::string& description)
	    : m_first("", "datasets", description, false, "", "D1 [D2...]", cmd),
	      m_more("more", "more dataset directories", false, "D2...", cmd)
	{
	}

	/** Every directory given, in order; empty without --datasets (TCLAP
	 * reads values through non-const getters). */
	std::vector<std::string> values()
	{
		if (m_first.getValue().empty()) return {};
		std::vector<std::string> v{m_first.getValue()};
		for (const auto& d : m_more.getValue()) v.push_back(d);
		return v;
	}

private:
	TCLAP::ValueArg<std::string> m_first;
	TCLAP::UnlabeledMultiArg<std::string> m_more;
};

}  // namespace semnav
