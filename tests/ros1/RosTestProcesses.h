/* semnav: semantic navigation from tilting-laser sweeps */
// Processes for the ROS 1 tests: children that die with the test, a private
// rosmaster on a free port, and the emulated robot (semnav-device-emulator
// --base).
#pragma once

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace semnav::test
{
/** A child process (fork + exec, stdout and stderr to `logFile`), killed
 * by the kernel if the test dies (PR_SET_PDEATHSIG) and by the destructor
 * (SIGTERM, then SIGKILL after 3 s). */
class ChildProcess
{
public:
	ChildProcess(
	    const std::vector<std::string>& argv, const std::string& logFile)
	    : m_log(logFile)
	{
		const pid_t parent = ::getpid();
		m_pid = ::fork();
		if (m_pid < 0) throw std::runtime_error("fork failed");
		if (m_pid == 0)
		{
			::prctl(PR_SET_PDEATHSIG, SIGKILL);
			if (::getppid() != parent) ::_exit(127);
			::setpgid(0, 0);
			const int fd =
			    ::open(logFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
			::dup2(fd, 1);
			::dup2(fd, 2);
			std::vector<char*> args;
			for (const auto& a : argv)
				args.push_back(const_cast<char*>(a.c_str()));
			args.push_back(nullptr);
			::execvp(args[0], args.data());
			::_exit(127);
		}
	}
	~ChildProcess() { terminate(3.0); }
	ChildProcess(const ChildProcess&) = delete;
	ChildProcess& operator=(const ChildProcess&) = delete;

	pid_t pid() const { return m_pid; }
	void signal(int sig) const
	{
		if (m_pid > 0) ::kill(m_pid, sig);
	}
	/** SIGTERM, waits up to `grace` s, then SIGKILL; returns the exit code
	 * (-1 when killed or already reaped). */
	int terminate(double grace)
	{
		if (m_pid <= 0) return -1;
		::kill(m_pid, SIGCONT);
		::kill(m_pid, SIGTERM);
		const auto end = std::chrono::steady_clock::now() +
		                 std::chrono::duration<double>(grace);
		int status = 0;
		while (::waitpid(m_pid, &status, WNOHANG) == 0)
		{
			if (std::chrono::steady_clock::now() > end)
			{
				::kill(m_pid, SIGKILL);
				::waitpid(m_pid, &status, 0);
				break;
			}
			std::this_thread::sleep_for(std::chrono::milliseconds(10));
		}
		m_pid = -1;
		return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
	}
	/** SIGKILL and reap. */
	void kill()
	{
		if (m_pid <= 0) return;
		::kill(m_pid, SIGKILL);
		::waitpid(m_pid, nullptr, 0);
		m_pid = -1;
	}
	/** The log's lines so far. */
	std::vector<std::string> lines() const
	{
		std::ifstream f(m_log);
		std::vector<std::string> out;
		for (std::string l; std::getline(f, l);) out.push_back(l);
		return out;
	}
	const std::string& logFile() const { return m_log; }

private:
	pid_t m_pid = -1;
	std::string m_log;
};

/** A TCP port nobody listens on now. */
inline int freePort()
{
	const int s = ::socket(AF_INET, SOCK_STREAM, 0);
	sockaddr_in a{};
	a.sin_family = AF_INET;
	a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
	a.sin_port = 0;
	::bind(s, reinterpret_cast<sockaddr*>(&a), sizeof(a));
	socklen_t n = sizeof(a);
	::getsockname(s, reinterpret_cast<sockaddr*>(&a), &n);
	::close(s);
	return ntohs(a.sin_port);
}

/** A fresh directory under the build tree for one test's files. */
inline std::string testDir(const std::string& name)
{
	const std::string d = std::string(SEMNAV_BINARY_DIR) + "/tests/ros1-" +
	                      name + "-" + std::to_string(::getpid());
	std::system(("rm -rf '" + d + "' && mkdir -p '" + d + "'").c_str());
	return d;
}

/** `rosmaster --core` on a free port; this process (and its children)
 * talk to it: ROS_MASTER_URI, ROS_IP = 127.0.0.1, ROS_HOME in `dir`. */
class PrivateRosMaster
{
public:
	explicit PrivateRosMaster(const std::string& dir)
	    : m_port(freePort()),
	      m_dir(dir),
	      m_process(start(m_port, dir), dir + "/rosmaster.log")
	{
	}
	int port() const { return m_port; }

private:
	static std::vector<std::string> start(int port, const std::string& dir)
	{
		const std::string uri = "http://127.0.0.1:" + std::to_string(port);
		::setenv("ROS_MASTER_URI", uri.c_str(), 1);
		::setenv("ROS_IP", "127.0.0.1", 1);
		::setenv("ROS_HOME", dir.c_str(), 1);
		return {"rosmaster", "--core", "-p", std::to_string(port)};
	}
	int m_port;
	std::string m_dir;
	ChildProcess m_process;
};

/** semnav-device-emulator --base in `scene` from `pose` ("x,y,yaw_deg"),
 * with `extra` arguments; waits for its first JSON line (the devices). */
class EmulatedRobot
{
public:
	EmulatedRobot(
	    const std::string& dir, const std::string& scene,
	    const std::string& pose, const std::vector<std::string>& extra = {})
	    : m_process(args(dir, scene, pose, extra), dir + "/emulator.log")
	{
		const auto end =
		    std::chrono::steady_clock::now() + std::chrono::seconds(20);
		while (std::chrono::steady_clock::now() < end)
		{
			for (const auto& l : m_process.lines())
				if (!l.empty() && l[0] == '{')
				{
					m_devices = nlohmann::json::parse(l);
					return;
				}
			std::this_thread::sleep_for(std::chrono::milliseconds(50));
		}
		throw std::runtime_error(
		    "the emulator did not start: see " + dir + "/emulator.log");
	}
	/** The LMS's terminal. */
	std::string lmsPath() const { return m_devices.at("lms"); }
	ChildProcess& process() { return m_process; }
	/** Stops it (SIGTERM) and returns its final counters. */
	nlohmann::json finish()
	{
		m_process.terminate(5.0);
		const auto lines = m_process.lines();
		for (auto it = lines.rbegin(); it != lines.rend(); ++it)
			if (!it->empty() && (*it)[0] == '{')
				return nlohmann::json::parse(*it);
		return {};
	}
	std::string trajectoryFile() const { return m_trajectory; }

private:
	std::vector<std::string> args(
	    const std::string& dir, const std::string& scene,
	    const std::string& pose, const std::vector<std::string>& extra)
	{
		m_trajectory = dir + "/trajectory.txt";
		std::vector<std::string> a{
		    std::string(SEMNAV_BINARY_DIR) +
		        "/apps/semnav-device-emulator/semnav-device-emulator",
		    "--scene",
		    scene,
		    "--pose",
		    pose,
		    "--base",
		    "--json",
		    "--trajectory",
		    m_trajectory};
		a.insert(a.end(), extra.begin(), extra.end());
		return a;
	}
	std::string m_trajectory;
	ChildProcess m_process;
	nlohmann::json m_devices;
};

}  // namespace semnav::test
