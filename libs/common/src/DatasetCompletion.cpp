/* semnav: semantic navigation from tilting-laser sweeps */
#include <fcntl.h>
#include <semnav/common/AtomicFile.h>
#include <semnav/common/DatasetCompletion.h>
#include <semnav/common/Error.h>
#include <unistd.h>

#include <filesystem>

namespace semnav
{
namespace fs = std::filesystem;

std::string DatasetCompletion::markerPath(
    const std::string& dir, const std::string& name)
{
	return (fs::path(dir) / (name + ".incomplete")).string();
}

void DatasetCompletion::begin(const std::string& dir, const std::string& name)
{
	const std::string marker = markerPath(dir, name);
	writeFileAtomically(
	    marker, "semnav-sim (pid " + std::to_string(::getpid()) +
	                ") is replacing the dataset " + name + "\n");
	// On disk before any file of the dataset is replaced.
	const int fd = ::open(marker.c_str(), O_RDONLY);
	if (fd >= 0)
	{
		::fsync(fd);
		::close(fd);
	}
}

void DatasetCompletion::end(const std::string& dir, const std::string& name)
{
	std::error_code ec;
	fs::remove(markerPath(dir, name), ec);
	if (ec)
		throw IoError(
		    "cannot remove " + markerPath(dir, name) + ": " + ec.message());
}

void DatasetCompletion::require(const std::string& dir, const std::string& name)
{
	const std::string marker = markerPath(dir, name);
	if (fs::exists(marker))
		throw IoError(
		    "dataset " + name + " in " + dir +
		    " is incomplete (its writer was interrupted; " + marker +
		    "): simulate it again");
}

}  // namespace semnav
