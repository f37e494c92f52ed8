/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/math/TPoint3D.h>
#include <mrpt/poses/CPose2D.h>
#include <semnav/robot/ObstacleSource.h>

#include <mutex>
#include <vector>

namespace semnav
{
class RobotBase;
class Sweep;

/** Obstacles from the latest sweep: its points between the floor and the
 * robot's height, within range, kept in the odometry frame and handed to
 * the navigator in the robot frame of now (odometry since the sweep).
 * Older than max_age_s, or before the first sweep, they count as blocked
 * (sense() returns false). Thread-safe.
 *
 * Options: INI section [SweepObstacles] (config/navigation.ini). */
class SweepObstacles : public ObstacleSource
{
public:
	struct TOptions : public mrpt::config::CLoadableOptions
	{
		void loadFromConfigFile(
		    const mrpt::config::CConfigFileBase& c,
		    const std::string& section) override;
		void saveToConfigFile(
		    mrpt::config::CConfigFileBase& c,
		    const std::string& section) const override;

		/** min_height_m, max_height_m: points between these heights
		 * (robot frame) are obstacles: above the floor, below the top of
		 * the robot. */
		double minHeight = 0.05;
		double maxHeight = 1.0;
		/** max_range_m: farther points are ignored. */
		double maxRange = 5.0;
		/** max_age_s: older obstacles count as blocked. */
		double maxAge = 60.0;
		/** cell_m: points are thinned to one per cell of this size. */
		double cell = 0.05;
	};

	/** `base` gives the odometry now; it must outlive this object. */
	SweepObstacles(const RobotBase& base, const TOptions& options);

	/** Takes the obstacles of a new sweep (with its odometry). */
	void update(const Sweep& sweep);
	bool sense(
	    mrpt::maps::CSimplePointsMap& robotFrame,
	    mrpt::Clock::time_point& sensedAt) override;

	/** Points kept from the last sweep (odometry frame). */
	std::size_t size() const;
	const TOptions& options() const { return m_options; }

private:
	const RobotBase& m_base;
	TOptions m_options;
	mutable std::mutex m_mutex;
	std::vector<mrpt::math::TPoint3Df> m_points;
	mrpt::Clock::time_point m_time{};
	bool m_hasSweep = false;
};

}  // namespace semnav
