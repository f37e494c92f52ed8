/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/math/TPoint3D.h>
#include <mrpt/poses/CPose2D.h>
#include <semnav/robot/ObstacleSource.h>

#include <mutex>
#include <set>
#include <tuple>
#include <vector>

namespace semnav
{
class RobotBase;
class Sweep;

/** Obstacles from the latest stop's sweeps: their points between the floor
 * and the robot's height, within range, kept in the odometry frame and
 * handed to the navigator in the robot frame of now (odometry since the
 * sweep). Sweeps taken where the robot only turned since the previous one
 * (a stop-and-scan start) add up, so the 180 deg laser's views of one stop
 * cover what it saw around; a sweep taken elsewhere replaces them. Older
 * than max_age_s (the latest sweep), or before the first sweep, they count
 * as blocked (sense() returns false). Thread-safe.
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

	/** Takes the obstacles of a new sweep (with its odometry): added to
	 * those of the previous sweep when the robot has not moved more than
	 * cell_m since, else in their place. */
	void update(const Sweep& sweep);
	bool sense(
	    mrpt::maps::CSimplePointsMap& robotFrame,
	    mrpt::Clock::time_point& sensedAt) override;

	/** Points kept from the last stop's sweeps (odometry frame). */
	std::size_t size() const;
	const TOptions& options() const { return m_options; }

private:
	const RobotBase& m_base;
	TOptions m_options;
	mutable std::mutex m_mutex;
	std::vector<mrpt::math::TPoint3Df> m_points;
	/** Cells of m_points (thinning). */
	std::set<std::tuple<long, long, long>> m_cells;
	/** Odometry of the latest sweep. */
	mrpt::poses::CPose2D m_at;
	mrpt::Clock::time_point m_time{};
	bool m_hasSweep = false;
};

}  // namespace semnav
