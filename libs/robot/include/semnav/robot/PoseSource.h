/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/math/TPose2D.h>

namespace semnav
{
/** Where the robot is in the map, as the navigator sees it: the
 * localizer's estimate composed with the odometry since (LocalizedPose),
 * or in a simulation the true pose. */
class PoseSource
{
public:
	virtual ~PoseSource() = default;
	/** The robot's pose in the map frame now. */
	virtual mrpt::math::TPose2D pose() const = 0;
};

}  // namespace semnav
