/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/poses/CPose2D.h>

#include <string>
#include <vector>

namespace semnav
{
/** The ground truth semnav-sim writes next to `<name>.rawlog` (docs/design.md):
 * `<name>.gt.txt` (per sweep: `index timestamp x y yaw_rad`, '#' comments)
 * and `<name>.labels/sweep_NNNN.png`. */
class GroundTruthLog
{
public:
	/** Opens `<dir>/<name>.gt.txt`; throws IoError naming the file (and
	 * the line of a malformed entry). */
	GroundTruthLog(const std::string& dir, const std::string& name);

	/** The ground truth of a rawlog: name = the rawlog's file stem. */
	static GroundTruthLog forRawlog(
	    const std::string& gtDir, const std::string& rawlogPath);

	std::size_t size() const { return m_poses.size(); }
	/** True pose of sweep i; throws IoError when there is none. */
	const mrpt::poses::CPose2D& pose(std::size_t i) const;
	/** Path of the label image of sweep i (may not exist). */
	std::string labelImagePath(std::size_t i) const;
	const std::string& labelsDir() const { return m_labelsDir; }

private:
	std::string m_file, m_labelsDir;
	std::vector<mrpt::poses::CPose2D> m_poses;
	std::vector<bool> m_has;
};

}  // namespace semnav
