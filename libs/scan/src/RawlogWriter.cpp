/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt/serialization/archiveFrom_std_streams.h>
#include <semnav/common/Error.h>
#include <semnav/scan/RawlogWriter.h>
#include <unistd.h>

#include <filesystem>

namespace semnav
{
RawlogWriter::RawlogWriter(std::string path, int compressLevel, Mode mode)
    : m_path(std::move(path))
{
	if (mode == Mode::Streaming)
	{
		m_stream = std::make_unique<std::ofstream>(
		    m_path, std::ios::binary | std::ios::trunc);
		if (!*m_stream) throw IoError("cannot create rawlog " + m_path);
		return;
	}
	const std::filesystem::path p(m_path);
	m_tmpPath = (p.parent_path() / ("." + p.filename().string() + ".tmp" +
	                                std::to_string(::getpid())))
	                .string();
	m_out = std::make_unique<mrpt::io::CFileGZOutputStream>();
	std::string err;
	if (!m_out->open(m_tmpPath, compressLevel, err))
		throw IoError("cannot create rawlog " + m_path + ": " + err);
}

RawlogWriter::~RawlogWriter()
{
	if (m_stream) return;  // closed by its destructor, kept
	if (!m_committed)
	{
		m_out.reset();
		std::error_code ec;
		std::filesystem::remove(m_tmpPath, ec);
	}
}

void RawlogWriter::write(const mrpt::serialization::CSerializable& obj)
{
	if (m_committed) throw IoError("rawlog " + m_path + " already committed");
	try
	{
		if (m_stream)
		{
			mrpt::serialization::CArchiveStreamBase<std::ostream> arch(
			    *m_stream);
			arch << obj;
			m_stream->flush();
			if (!*m_stream) throw IoError("write failed");
		}
		else
		{
			auto arch = mrpt::serialization::archiveFrom(*m_out);
			arch << obj;
		}
	}
	catch (const std::exception& e)
	{
		throw IoError("cannot write rawlog " + m_path + ": " + e.what());
	}
	m_count++;
}

void RawlogWriter::commit()
{
	if (m_committed) return;
	if (m_stream)
	{
		m_stream->close();
		m_committed = true;
		return;
	}
	m_out->close();
	std::error_code ec;
	std::filesystem::rename(m_tmpPath, m_path, ec);
	if (ec)
		throw IoError("cannot write rawlog " + m_path + ": " + ec.message());
	m_committed = true;
}

}  // namespace semnav
