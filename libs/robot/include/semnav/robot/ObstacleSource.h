/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/core/Clock.h>
#include <mrpt/maps/CSimplePointsMap.h>

namespace semnav
{
/** Where the navigator's obstacles come from: the latest stop's sweep points
 * (SweepObstacles) or, in a simulation, a horizontal ray cast in the
 * scene. */
class ObstacleSource
{
public:
	virtual ~ObstacleSource() = default;
	/** Obstacle points in the robot frame now, and when they were sensed.
	 * False when there are none to trust (too old, sensor gone): MRPT's
	 * navigator then stops the robot, i.e. the way counts as blocked. */
	virtual bool sense(
	    mrpt::maps::CSimplePointsMap& robotFrame,
	    mrpt::Clock::time_point& sensedAt) = 0;
};

}  // namespace semnav
