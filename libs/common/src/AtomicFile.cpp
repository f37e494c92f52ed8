/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/AtomicFile.h>
#include <semnav/common/Error.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

namespace semnav
{
void writeAtomically(
    const std::string& path,
    const std::function<void(const std::string& tmpPath)>& write)
{
	namespace fs = std::filesystem;
	const fs::path target(path);
	const fs::path tmp =
	    target.parent_path() / ("." + target.filename().string() + ".tmp" +
	                            std::to_string(::getpid()));
	try
	{
		write(tmp.string());
	}
	catch (...)
	{
		std::error_code ec;
		fs::remove(tmp, ec);
		throw;
	}
	std::error_code ec;
	fs::rename(tmp, target, ec);
	if (ec)
	{
		fs::remove(tmp, ec);
		throw IoError("cannot write " + path + ": " + ec.message());
	}
}

void writeFileAtomically(const std::string& path, const std::string& content)
{
	writeAtomically(
	    path,
	    [&](const std::string& tmp)
	    {
		    std::ofstream f(tmp, std::ios::binary);
		    if (!f) throw IoError("cannot create " + tmp);
		    f.write(
		        content.data(), static_cast<std::streamsize>(content.size()));
		    f.close();
		    if (!f) throw IoError("cannot write " + tmp);
	    });
}

void createDirectories(const std::string& path)
{
	std::error_code ec;
	std::filesystem::create_directories(path, ec);
	if (ec)
		throw IoError("cannot create directory " + path + ": " + ec.message());
}

}  // namespace semnav
