/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/scan/RawlogSweepSource.h>

namespace semnav
{
RawlogSweepSource::RawlogSweepSource(
    const std::string& path, const SweepAssembler::TOptions& options)
    : m_reader(path, options)
{
}

bool RawlogSweepSource::next(Sweep& sweep, mrpt::Clock::time_point notBefore)
{
	while (m_end == End::None)
	{
		if (m_cancelled)
		{
			m_end = End::Cancelled;
			break;
		}
		if (!m_reader.next(sweep))
		{
			m_end = End::EndOfLog;
			break;
		}
		if (!sweep.quality().complete)
		{
			m_skipped++;
			continue;
		}
		if (sweep.timestamp() < notBefore) continue;
		m_returned++;
		return true;
	}
	return false;
}

std::string RawlogSweepSource::endMessage() const
{
	if (m_end == End::None) return "";
	return m_reader.path() + ": " + endName(m_end) + " after " +
	       std::to_string(m_returned) + " complete sweeps (" +
	       std::to_string(m_skipped) + " incomplete skipped)";
}

}  // namespace semnav
