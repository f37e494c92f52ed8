/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace semnav::test
{
/** Exit code, stdout and stderr of one run of a semnav app. */
struct AppRun
{
	int code;
	std::string out, err;
};

/** Runs build/apps/<app>/<app> with `args` (shell words). */
inline AppRun runApp(const std::string& app, const std::string& args)
{
	namespace fs = std::filesystem;
	const fs::path tmp = fs::temp_directory_path() /
	                     ("semnav_apprun_" + std::to_string(::getpid()));
	fs::create_directories(tmp);
	const std::string errFile = (tmp / (app + "_stderr.txt")).string();
	const std::string cmd = std::string(SEMNAV_BINARY_DIR) + "/apps/" + app +
	                        "/" + app + " " + args + " 2>" + errFile;
	AppRun r{};
	FILE* p = ::popen(cmd.c_str(), "r");
	std::array<char, 4096> buf{};
	std::size_t n;
	while ((n = std::fread(buf.data(), 1, buf.size(), p)) > 0)
		r.out.append(buf.data(), n);
	const int status = ::pclose(p);
	r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
	std::ifstream e(errFile);
	r.err.assign(std::istreambuf_iterator<char>(e), {});
	return r;
}

/** Number of lines of a text. */
inline std::size_t lineCount(const std::string& s)
{
	return static_cast<std::size_t>(std::count(s.begin(), s.end(), '\n'));
}

}  // namespace semnav::test
