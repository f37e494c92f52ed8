/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/robot/ObstacleSource.h>

namespace semnav
{
class SimulatedBase;

/** The simulated robot's obstacle sensor: horizontal scans (one plane per
 * scan_heights_m, from the robot's centre at its true pose) ray-cast in
 * the scene itself, not in the map (the map may be wrong). */
class RayCastObstacles : public ObstacleSource
{
public:
	/** `base` (its scene and options) must outlive this object. */
	explicit RayCastObstacles(const SimulatedBase& base);

	bool sense(
	    mrpt::maps::CSimplePointsMap& robotFrame,
	    mrpt::Clock::time_point& sensedAt) override;

private:
	const SimulatedBase& m_base;
};

}  // namespace semnav
