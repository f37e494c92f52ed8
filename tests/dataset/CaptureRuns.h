/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

extern char** environ;

namespace semnav::test
{
/** Exit code and stdout of a shell command. */
struct ShellRun
{
	int code = -1;
	std::string out;
};

/** Runs `cmd` with sh, stdin from /dev/null. */
inline ShellRun shell(const std::string& cmd)
{
	ShellRun r;
	FILE* p = ::popen((cmd + " </dev/null").c_str(), "r");
	if (!p) return r;
	std::array<char, 4096> buf{};
	std::size_t n;
	while ((n = std::fread(buf.data(), 1, buf.size(), p)) > 0)
		r.out.append(buf.data(), n);
	const int st = ::pclose(p);
	r.code = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
	return r;
}

/** Holds an exclusive lock on a file while alive: the runs against the
 * device emulators are timing-sensitive, so two of them (capture tests,
 * live sweep source) never run at once, even under ctest -j. */
class CaptureRunLock
{
public:
	CaptureRunLock()
	    : m_fd(::open(
	          (std::filesystem::temp_directory_path() /
	           "semnav_capture_selftest.lock")
	              .c_str(),
	          O_CREAT | O_RDWR | O_CLOEXEC, 0666))
	{
		if (m_fd >= 0) ::flock(m_fd, LOCK_EX);
	}
	~CaptureRunLock()
	{
		if (m_fd >= 0) ::close(m_fd);
	}
	CaptureRunLock(const CaptureRunLock&) = delete;
	CaptureRunLock& operator=(const CaptureRunLock&) = delete;

private:
	int m_fd;
};

/** A program running in the background with stdout and stderr to `log`;
 * SIGTERM and waited for when destroyed. */
class BackgroundProcess
{
public:
	BackgroundProcess(std::vector<std::string> argv, const std::string& log)
	{
		posix_spawn_file_actions_t fa;
		posix_spawn_file_actions_init(&fa);
		posix_spawn_file_actions_addopen(
		    &fa, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
		posix_spawn_file_actions_adddup2(&fa, 1, 2);
		posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
		std::vector<char*> args;
		for (auto& a : argv) args.push_back(a.data());
		args.push_back(nullptr);
		if (::posix_spawn(&m_pid, args[0], &fa, nullptr, args.data(), environ))
			m_pid = -1;
		posix_spawn_file_actions_destroy(&fa);
	}
	~BackgroundProcess() { stop(); }
	BackgroundProcess(const BackgroundProcess&) = delete;
	BackgroundProcess& operator=(const BackgroundProcess&) = delete;

	bool running() const { return m_pid > 0 && ::kill(m_pid, 0) == 0; }
	/** SIGTERM, then waits; the exit code (-1 when killed or not run). */
	int stop()
	{
		if (m_pid <= 0) return m_code;
		::kill(m_pid, SIGTERM);
		int st = 0;
		::waitpid(m_pid, &st, 0);
		m_pid = -1;
		m_code = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
		return m_code;
	}

private:
	pid_t m_pid = -1;
	int m_code = -1;
};

}  // namespace semnav::test
