/* semnav: semantic navigation from tilting-laser sweeps */
#include <fcntl.h>
#include <semnav/common/AtomicFile.h>
#include <semnav/common/Error.h>
#include <semnav/nav/NavLogFile.h>
#include <semnav/nav/SemanticNavigator.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <csignal>
#include <cstring>
#include <filesystem>

namespace semnav
{
namespace
{
/** The directory removeOnTermination() watches (fixed storage: read in a
 * signal handler). */
char g_privateDir[4096];

/** Async-signal-safe removal of a flat directory (the log files MRPT
 * writes), then the signal's default action. */
void removePrivateDirectory(int sig)
{
	const int fd = ::open(g_privateDir, O_RDONLY | O_DIRECTORY);
	if (fd >= 0)
	{
		alignas(8) char buf[4096];
		long n;
		while ((n = ::syscall(SYS_getdents64, fd, buf, sizeof(buf))) > 0)
			for (long off = 0; off < n;)
			{
				// struct linux_dirent64: ino, off, reclen, type, name.
				unsigned short reclen;
				std::memcpy(&reclen, buf + off + 16, sizeof(reclen));
				const char* name = buf + off + 19;
				if (std::strcmp(name, ".") != 0 && std::strcmp(name, "..") != 0)
					::unlinkat(fd, name, 0);
				off += reclen;
			}
		::close(fd);
		::rmdir(g_privateDir);
	}
	std::signal(sig, SIG_DFL);
	std::raise(sig);
}
}  // namespace

std::string NavLogFile::privateDirectory(const std::string& path)
{
	const auto parent = std::filesystem::path(path).parent_path();
	const auto dir = parent.empty() ? std::filesystem::path(".") : parent;
	return (dir / (".navlog-" + std::to_string(::getpid()))).string();
}

void NavLogFile::removeOnTermination(const std::string& path)
{
	if (path.empty()) return;
	const std::string dir = privateDirectory(path);
	if (dir.size() >= sizeof(g_privateDir)) return;
	std::memcpy(g_privateDir, dir.c_str(), dir.size() + 1);
	for (const int sig : {SIGINT, SIGTERM, SIGHUP})
		std::signal(sig, removePrivateDirectory);
}

NavLogFile::NavLogFile(SemanticNavigator& nav, const std::string& path)
    : m_nav(nav), m_path(path)
{
	if (m_path.empty()) return;
	m_dir = privateDirectory(m_path);
	createDirectories(std::filesystem::path(m_dir).parent_path().string());
	std::filesystem::remove_all(m_dir);
	m_nav.setNavLogDirectory(m_dir);
}

NavLogFile::~NavLogFile()
{
	if (!m_dir.empty()) std::filesystem::remove_all(m_dir);
}

std::string NavLogFile::finish()
{
	if (m_dir.empty()) return "";
	m_nav.setNavLogDirectory("");  // closes the file
	std::string written;
	for (const auto& e : std::filesystem::directory_iterator(m_dir))
		if (e.path().extension() == ".reactivenavlog")
			written = e.path().string();
	if (written.empty())
		throw IoError("MRPT wrote no navigation log in " + m_dir);
	std::filesystem::rename(written, m_path);
	return m_path;
}

}  // namespace semnav
