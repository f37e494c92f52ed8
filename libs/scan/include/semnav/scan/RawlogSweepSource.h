/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/scan/RawlogSweepReader.h>
#include <semnav/scan/SweepSource.h>

#include <atomic>
#include <string>

namespace semnav
{
/** The complete sweeps of a rawlog file (RawlogSweepReader), as a
 * SweepSource: replaying a capture through the robot's code path.
 * Incomplete sweeps are skipped and counted. A corrupt or truncated file
 * throws RawlogError (naming the file) once its readable sweeps are out. */
class RawlogSweepSource : public SweepSource
{
public:
	/** Throws RawlogError when the file cannot be opened. */
	explicit RawlogSweepSource(
	    const std::string& path,
	    const SweepAssembler::TOptions& options = SweepAssembler::TOptions());

	bool next(Sweep& sweep, mrpt::Clock::time_point notBefore = {}) override;
	void cancel() override { m_cancelled = true; }
	End end() const override { return m_end; }
	std::string endMessage() const override;

	/** Incomplete sweeps skipped so far. */
	std::size_t skippedIncomplete() const { return m_skipped; }
	const RawlogSweepReader& reader() const { return m_reader; }

private:
	RawlogSweepReader m_reader;
	std::atomic<bool> m_cancelled{false};
	End m_end = End::None;
	std::size_t m_skipped = 0, m_returned = 0;
};

}  // namespace semnav
