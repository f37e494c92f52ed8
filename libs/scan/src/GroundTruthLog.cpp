/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/DatasetCompletion.h>
#include <semnav/common/Error.h>
#include <semnav/scan/GroundTruthLog.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace semnav
{
namespace fs = std::filesystem;

GroundTruthLog::GroundTruthLog(const std::string& dir, const std::string& name)
    : m_file((fs::path(dir) / (name + ".gt.txt")).string()),
      m_labelsDir((fs::path(dir) / (name + ".labels")).string())
{
	DatasetCompletion::require(dir, name);
	std::ifstream f(m_file);
	if (!f) throw IoError("cannot open ground truth " + m_file);
	std::string line;
	std::size_t lineNo = 0;
	while (std::getline(f, line))
	{
		lineNo++;
		const auto b = line.find_first_not_of(" \t\r");
		if (b == std::string::npos || line[b] == '#') continue;
		std::istringstream is(line);
		long index = -1;
		double t, x, y, yaw;
		if (!(is >> index >> t >> x >> y >> yaw) || index < 0)
			throw IoError(
			    m_file + ":" + std::to_string(lineNo) +
			    ": expected 'index timestamp x y yaw_rad'");
		const auto i = static_cast<std::size_t>(index);
		if (i >= m_poses.size())
		{
			m_poses.resize(i + 1);
			m_has.resize(i + 1, false);
		}
		m_poses[i] = mrpt::poses::CPose2D(x, y, yaw);
		m_has[i] = true;
	}
}

GroundTruthLog GroundTruthLog::forRawlog(
    const std::string& gtDir, const std::string& rawlogPath)
{
	return GroundTruthLog(gtDir, fs::path(rawlogPath).stem().string());
}

const mrpt::poses::CPose2D& GroundTruthLog::pose(std::size_t i) const
{
	if (i >= m_poses.size() || !m_has[i])
		throw IoError(m_file + " has no pose for sweep " + std::to_string(i));
	return m_poses[i];
}

std::string GroundTruthLog::labelImagePath(std::size_t i) const
{
	char name[32];
	std::snprintf(name, sizeof(name), "sweep_%04zu.png", i);
	return (fs::path(m_labelsDir) / name).string();
}

}  // namespace semnav
