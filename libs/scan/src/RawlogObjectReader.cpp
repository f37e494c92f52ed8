/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/io/CMemoryStream.h>
#include <mrpt/serialization/CArchive.h>
#include <semnav/common/Error.h>
#include <semnav/scan/RawlogObjectReader.h>
#include <zlib.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "SerializedObjectChecker.h"

namespace semnav
{
/** The decompressed bytes of the file (zlib reads plain files as they
 * are), with zlib's errors and a missing gzip end reported, never taken for
 * the end of the data. */
class RawlogObjectReader::Input : public ByteSource
{
public:
	explicit Input(const std::string& path)
	{
		m_gz = ::gzopen(path.c_str(), "rb");
		if (!m_gz)
			throw RawlogError(
			    "cannot open rawlog " + path + ": " + std::strerror(errno));
		::gzbuffer(m_gz, 1 << 17);
	}
	~Input() override { ::gzclose(m_gz); }

	std::size_t read(std::uint8_t* dst, std::size_t n) override
	{
		std::size_t got = 0;
		while (got < n)
		{
			const unsigned chunk =
			    static_cast<unsigned>(std::min<std::size_t>(n - got, 1 << 30));
			const int r = ::gzread(m_gz, dst + got, chunk);
			if (r > 0)
			{
				got += static_cast<std::size_t>(r);
				continue;
			}
			int code = Z_OK;
			const char* msg = ::gzerror(m_gz, &code);
			if (code == Z_BUF_ERROR)  // zlib: "unexpected end of file"
				throw SerializedFormatError(
				    "the gzip data ends early (file cut short)", true);
			if (r < 0 || code != Z_OK)
				throw SerializedFormatError(
				    std::string("gzip data error: ") + (msg ? msg : "?"),
				    false);
			break;  // the clean end
		}
		return got;
	}

private:
	gzFile m_gz = nullptr;
};

RawlogObjectReader::RawlogObjectReader(const std::string& path) : m_path(path)
{
	std::error_code ec;
	if (!std::filesystem::exists(path, ec))
		throw RawlogError("cannot open rawlog " + path + ": no such file");
	if (std::filesystem::is_directory(path, ec))
		throw RawlogError(
		    "cannot open rawlog " + path + ": is a directory, not a file");
	m_in = std::make_unique<Input>(path);
}

RawlogObjectReader::~RawlogObjectReader() = default;

bool RawlogObjectReader::next(mrpt::serialization::CSerializable::Ptr& obj)
{
	if (m_done) return false;
	const std::string where = " at object " + std::to_string(m_objects) +
	                          " (byte " + std::to_string(m_offset) +
	                          " of the decompressed data): ";
	SerializedObjectChecker checker(*m_in);
	try
	{
		if (!checker.readObject())
		{
			m_done = true;
			return false;
		}
	}
	catch (const SerializedFormatError& e)
	{
		m_done = true;
		throw RawlogError(
		    "rawlog " + m_path +
		    (e.truncated() ? " is truncated" : " is corrupt") + where +
		    e.what());
	}
	const auto& bytes = checker.bytes();
	try
	{
		mrpt::io::CMemoryStream mem;
		mem.assignMemoryNotOwn(bytes.data(), bytes.size());
		auto arch = mrpt::serialization::archiveFrom(mem);
		obj = arch.ReadObject();
		if (mem.getPosition() != bytes.size())
			throw std::runtime_error(
			    "MRPT read " + std::to_string(mem.getPosition()) + " of its " +
			    std::to_string(bytes.size()) + " bytes");
	}
	catch (const std::exception& e)
	{
		m_done = true;
		std::string what = e.what();
		// MRPT's messages are several lines; the last one is the cause.
		while (!what.empty() && what.back() == '\n') what.pop_back();
		const auto nl = what.rfind('\n');
		if (nl != std::string::npos) what = what.substr(nl + 1);
		throw RawlogError("rawlog " + m_path + " is corrupt" + where + what);
	}
	m_objects++;
	m_offset += bytes.size();
	return true;
}

}  // namespace semnav
