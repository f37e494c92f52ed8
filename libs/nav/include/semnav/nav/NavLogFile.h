/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <string>

namespace semnav
{
class SemanticNavigator;

/** MRPT's navigation log of a SemanticNavigator (for navlog-viewer) under
 * a path of the caller's choosing: MRPT writes it into a directory of its
 * own naming, so the log goes to a private directory next to the target
 * and finish() moves it there. The private directory is removed by the
 * destructor. An empty path logs nothing. */
class NavLogFile
{
public:
	NavLogFile(SemanticNavigator& nav, const std::string& path);
	~NavLogFile();
	NavLogFile(const NavLogFile&) = delete;
	NavLogFile& operator=(const NavLogFile&) = delete;
	/** Closes the log and moves it to the target; returns the target ("" for
	 * no log). Throws IoError when MRPT wrote none. */
	std::string finish();

	/** The private directory of a log to `path`: `.navlog-<pid>` beside it. */
	static std::string privateDirectory(const std::string& path);

	/** For apps with no signal handlers of their own: SIGINT, SIGTERM or
	 * SIGHUP first remove the private directory of a log to `path` (which the
	 * destructor, not run then, would have), then end the process as the
	 * signal would have. */
	static void removeOnTermination(const std::string& path);

private:
	SemanticNavigator& m_nav;
	std::string m_path, m_dir;
};

}  // namespace semnav
