/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/math/TPose2D.h>
#include <semnav/robot/PoseSource.h>

#include <mutex>

namespace semnav
{
class RobotBase;

/** The pose a localized robot reports: the last map-frame estimate (from
 * StopAndScanLocalizer) composed with the odometry travelled since. Before
 * the first estimate it reports the odometry pose itself (the odometry
 * frame is the map frame). Thread-safe. */
class LocalizedPose : public PoseSource
{
public:
	/** `base` gives the odometry and must outlive this object. */
	explicit LocalizedPose(const RobotBase& base);

	/** The robot was at `mapPose` when its odometry read `odometry`. */
	virtual void setEstimate(
	    const mrpt::math::TPose2D& mapPose,
	    const mrpt::math::TPose2D& odometry);
	bool hasEstimate() const;

	/** The estimate composed with the odometry since; wraps the heading. */
	mrpt::math::TPose2D pose() const override;
	/** The same for an odometry reading `odometry`. */
	mrpt::math::TPose2D poseAt(const mrpt::math::TPose2D& odometry) const;

private:
	const RobotBase& m_base;
	mutable std::mutex m_mutex;
	bool m_hasEstimate = false;
	/** Map pose of the odometry frame: pose = m_odoToMap + odometry. */
	mrpt::math::TPose2D m_odoToMap;
};

}  // namespace semnav
