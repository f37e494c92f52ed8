/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/serialization/CSerializable.h>

#include <fstream>
#include <memory>
#include <string>

namespace mrpt::io
{
class CFileGZOutputStream;
}

namespace semnav
{
/** Writes an MRPT observation-only rawlog (gz-compressed, as MRPT's own
 * tools write them) atomically: objects go to a temporary file that
 * commit() renames to the final path. Destroying an uncommitted writer
 * removes the temporary, so an interrupted run never leaves a partial
 * rawlog under the final name.
 *
 * Streaming (a recording on a robot, which must survive the process being
 * killed): objects go straight to the final path, uncompressed (MRPT reads
 * plain and gz rawlogs alike), flushed after each one, so the file holds
 * every object written until the end. */
class RawlogWriter
{
public:
	enum class Mode
	{
		Atomic,
		Streaming
	};
	/** Opens the temporary file (Atomic) or the final one (Streaming);
	 * throws IoError. compressLevel 0..9 (Atomic only). */
	explicit RawlogWriter(
	    std::string path, int compressLevel = 1, Mode mode = Mode::Atomic);
	~RawlogWriter();
	RawlogWriter(const RawlogWriter&) = delete;
	RawlogWriter& operator=(const RawlogWriter&) = delete;

	/** Appends one observation (or any serializable object). */
	void write(const mrpt::serialization::CSerializable& obj);
	/** Closes and renames to the final path; throws IoError. */
	void commit();

	std::size_t count() const { return m_count; }
	const std::string& path() const { return m_path; }

private:
	std::string m_path, m_tmpPath;
	std::unique_ptr<mrpt::io::CFileGZOutputStream> m_out;
	std::unique_ptr<std::ofstream> m_stream;
	std::size_t m_count = 0;
	bool m_committed = false;
};

}  // namespace semnav
