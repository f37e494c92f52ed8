/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/scan/RawlogObjectReader.h>
#include <semnav/scan/SweepAssembler.h>

#include <memory>
#include <string>

namespace semnav
{
/** Reads the sweeps of a rawlog file, one at a time.
 *
 * Accepts observation-only rawlogs (semnav-sim's, rawlog-grabber's) and the
 * older sensory-frame format (CSensoryFrame + CActionCollection; odometry
 * increments are accumulated), through RawlogObjectReader (bounded, checked
 * deserialization). When the file is corrupt or truncated, next() first
 * returns every sweep that could be read (the last one flagged incomplete)
 * and then throws RawlogError naming the file and where the damage is. A
 * file without a sweep (empty, odometry only) just ends: callers that need
 * sweeps say noSweepsMessage(). */
class RawlogSweepReader
{
public:
	/** Throws RawlogError when the file cannot be opened. */
	explicit RawlogSweepReader(
	    const std::string& path,
	    const SweepAssembler::TOptions& options = SweepAssembler::TOptions());
	~RawlogSweepReader();

	/** Next sweep; false at the end of the file. */
	bool next(Sweep& out);

	/** Objects read from the file so far. */
	std::size_t objectsRead() const { return m_in.objectsRead(); }
	const SweepAssembler& assembler() const { return m_assembler; }
	const std::string& path() const { return m_path; }
	/** "no sweeps in <path> (N objects, L scan lines)". */
	std::string noSweepsMessage() const;

private:
	void readMore();
	void push(const mrpt::serialization::CSerializable::Ptr& obj);

	std::string m_path;
	RawlogObjectReader m_in;
	SweepAssembler m_assembler;
	std::size_t m_lines = 0;  ///< scan lines among the objects
	bool m_eof = false;
	std::string m_error;
	mrpt::poses::CPose2D m_actionOdometry;
};

/** Reads all sweeps of a rawlog; throws RawlogError on a corrupt file or
 * one without a sweep. */
std::vector<Sweep> readRawlogSweeps(
    const std::string& path,
    const SweepAssembler::TOptions& options = SweepAssembler::TOptions());

}  // namespace semnav
