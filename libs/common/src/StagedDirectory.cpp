/* semnav: semantic navigation from tilting-laser sweeps */
#include <fcntl.h>
#include <semnav/common/AtomicFile.h>
#include <semnav/common/Error.h>
#include <semnav/common/StagedDirectory.h>
#include <signal.h>
#include <stdio.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

namespace semnav
{
namespace fs = std::filesystem;

namespace
{
/** `target` without a trailing separator ("map/" -> "map"). */
fs::path normalized(const std::string& target)
{
	fs::path p = fs::path(target).lexically_normal();
	if (p.filename().empty()) p = p.parent_path();
	return p;
}

fs::path parentOf(const fs::path& p)
{
	return p.has_parent_path() ? p.parent_path() : fs::path(".");
}

/** Sibling `.<name>.<kind>-<pid>`. */
fs::path sibling(const fs::path& target, const char* kind, long pid)
{
	return parentOf(target) / ("." + target.filename().string() + "." + kind +
	                           "-" + std::to_string(pid));
}

bool processAlive(long pid)
{
	return ::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM;
}

/** Siblings `.<name>.<kind>-<pid>` of `target`, with their pid. */
template <typename F>
void forEachSibling(const fs::path& target, F&& f)
{
	const std::string prefix = "." + target.filename().string() + ".";
	std::error_code ec;
	for (const auto& e : fs::directory_iterator(parentOf(target), ec))
	{
		const std::string n = e.path().filename().string();
		if (n.rfind(prefix, 0) != 0) continue;
		const std::string rest = n.substr(prefix.size());
		const auto dash = rest.rfind('-');
		if (dash == std::string::npos) continue;
		char* end = nullptr;
		const long pid = std::strtol(rest.c_str() + dash + 1, &end, 10);
		if (*end != '\0' || pid <= 0) continue;
		f(e.path(), rest.substr(0, dash), pid);
	}
}

/** Staging directories of dead processes: a complete one ("ready") becomes
 * the target if there is none, the rest is removed. */
void cleanUpAfterDeadWriters(const fs::path& target)
{
	forEachSibling(
	    target,
	    [&](const fs::path& p, const std::string& kind, long pid)
	    {
		    if (processAlive(pid)) return;
		    std::error_code ec;
		    if (kind == "ready" && !fs::exists(target))
			    fs::rename(p, target, ec);
		    else if (kind == "new" || kind == "old" || kind == "ready")
			    fs::remove_all(p, ec);
	    });
}

void fsyncPath(const fs::path& p, bool dir)
{
	const int fd = ::open(p.c_str(), dir ? O_RDONLY | O_DIRECTORY : O_RDONLY);
	if (fd < 0) return;
	::fsync(fd);
	::close(fd);
}

/** Every file and directory under `dir` on disk before the swap. */
void fsyncTree(const fs::path& dir)
{
	for (const auto& e : fs::recursive_directory_iterator(dir))
		fsyncPath(e.path(), e.is_directory());
	fsyncPath(dir, true);
}

void renameOrThrow(const fs::path& from, const fs::path& to)
{
	if (::rename(from.c_str(), to.c_str()) != 0)
		throw IoError(
		    "cannot rename " + from.string() + " to " + to.string() + ": " +
		    std::strerror(errno));
}
}  // namespace

StagedDirectory::StagedDirectory(const std::string& target, OwnEntry ownEntry)
    : m_ownEntry(std::move(ownEntry))
{
	const fs::path t = normalized(target);
	m_target = t.string();
	if (t.empty() || t.filename() == "." || t.filename() == "..")
		throw IoError(
		    "cannot replace the directory '" + target + "' as a whole");
	createDirectories(parentOf(t).string());
	cleanUpAfterDeadWriters(t);
	m_staged = sibling(t, "new", ::getpid()).string();
	std::error_code ec;
	fs::remove_all(m_staged, ec);
	createDirectories(m_staged);
}

StagedDirectory::~StagedDirectory()
{
	if (m_committed) return;
	std::error_code ec;
	fs::remove_all(m_staged, ec);
}

void StagedDirectory::commit()
{
	const fs::path t(m_target), staged(m_staged);
	checkReplaceable(m_target, m_ownEntry);
	fsyncTree(staged);
	if (!fs::exists(t))
		renameOrThrow(staged, t);
	else if (
	    ::renameat2(
	        AT_FDCWD, staged.c_str(), AT_FDCWD, t.c_str(), RENAME_EXCHANGE) ==
	    0)
	{
		// `staged` now holds the old directory.
	}
	else if (errno == EINVAL || errno == ENOSYS || errno == ENOTSUP)
	{
		const fs::path ready = sibling(t, "ready", ::getpid());
		renameOrThrow(staged, ready);
		renameOrThrow(t, staged);
		renameOrThrow(ready, t);
	}
	else
		throw IoError(
		    "cannot replace " + m_target + ": " + std::strerror(errno));
	m_committed = true;
	fsyncPath(parentOf(t), true);
	std::error_code ec;
	fs::remove_all(staged, ec);
}

void StagedDirectory::checkReplaceable(
    const std::string& target, const OwnEntry& ownEntry)
{
	const fs::path t = normalized(target);
	if (!fs::exists(t)) return;
	if (!fs::is_directory(t))
		throw IoError(t.string() + " exists and is not a directory");
	for (const auto& e : fs::directory_iterator(t))
		if (!ownEntry(e.path().filename().string()))
			throw IoError(
			    "not replacing " + t.string() + ": it holds " +
			    e.path().filename().string() +
			    ", which is not ours (write into a directory of its own)");
}

std::string StagedDirectory::interruptedSave(const std::string& target)
{
	const fs::path t = normalized(target);
	std::string found;
	if (t.empty() || fs::exists(t)) return found;
	forEachSibling(
	    t,
	    [&](const fs::path& p, const std::string& kind, long)
	    {
		    if (kind == "ready") found = p.string();
	    });
	return found;
}

}  // namespace semnav
