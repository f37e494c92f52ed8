/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/math/wrap2pi.h>
#include <mrpt/poses/CPose2D.h>
#include <semnav/robot/LocalizedPose.h>
#include <semnav/robot/RobotBase.h>

namespace semnav
{
LocalizedPose::LocalizedPose(const RobotBase& base) : m_base(base) {}

void LocalizedPose::setEstimate(
    const mrpt::math::TPose2D& mapPose, const mrpt::math::TPose2D& odometry)
{
	std::lock_guard<std::mutex> lock(m_mutex);
	m_odoToMap =
	    (mrpt::poses::CPose2D(mapPose) + (-mrpt::poses::CPose2D(odometry)))
	        .asTPose();
	m_hasEstimate = true;
}

bool LocalizedPose::hasEstimate() const
{
	std::lock_guard<std::mutex> lock(m_mutex);
	return m_hasEstimate;
}

mrpt::math::TPose2D LocalizedPose::poseAt(
    const mrpt::math::TPose2D& odometry) const
{
	std::lock_guard<std::mutex> lock(m_mutex);
	if (!m_hasEstimate) return odometry;
	auto p = (mrpt::poses::CPose2D(m_odoToMap) + mrpt::poses::CPose2D(odometry))
	             .asTPose();
	p.phi = mrpt::math::wrapToPi(p.phi);
	return p;
}

mrpt::math::TPose2D LocalizedPose::pose() const
{
	return poseAt(m_base.odometry().pose);
}

}  // namespace semnav
