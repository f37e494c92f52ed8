/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <fcntl.h>
#include <unistd.h>

#include <cstdio>
#include <iostream>

namespace semnav
{
/** Sends stderr to /dev/null while alive: Debian's liboctomap prints debug
 * output ("Reading binary octree type OcTree"), libpng and OpenCV print
 * their own lines on corrupt images; errors stay one line, ours. */
class QuietStderr
{
public:
	QuietStderr()
	{
		std::fflush(stderr);
		std::cerr.flush();
		m_saved = ::dup(2);
		const int devnull = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
		if (devnull >= 0)
		{
			::dup2(devnull, 2);
			::close(devnull);
		}
	}
	~QuietStderr()
	{
		std::fflush(stderr);
		std::cerr.flush();
		if (m_saved >= 0)
		{
			::dup2(m_saved, 2);
			::close(m_saved);
		}
	}
	QuietStderr(const QuietStderr&) = delete;
	QuietStderr& operator=(const QuietStderr&) = delete;

private:
	int m_saved = -1;
};

}  // namespace semnav
