/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/AtomicFile.h>
#include <semnav/common/Error.h>
#include <semnav/nav/NavLogFile.h>
#include <semnav/nav/SemanticNavigator.h>
#include <unistd.h>

#include <filesystem>

namespace semnav
{
NavLogFile::NavLogFile(SemanticNavigator& nav, const std::string& path)
    : m_nav(nav), m_path(path)
{
	if (m_path.empty()) return;
	const auto parent = std::filesystem::path(m_path).parent_path();
	const auto dir = parent.empty() ? std::filesystem::path(".") : parent;
	createDirectories(dir.string());
	m_dir = (dir / (".navlog-" + std::to_string(::getpid()))).string();
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
