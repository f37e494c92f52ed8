/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/serialization/CSerializable.h>

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
 * rawlog under the final name. */
class RawlogWriter
{
public:
	/** Opens the temporary file; throws IoError. compressLevel 0..9. */
	explicit RawlogWriter(std::string path, int compressLevel = 1);
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
	std::size_t m_count = 0;
	bool m_committed = false;
};

}  // namespace semnav
