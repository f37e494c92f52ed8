/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/OptionTable.h>
#include <semnav/robot/RobotBase.h>
#include <semnav/robot/SweepObstacles.h>
#include <semnav/scan/Sweep.h>

#include <cmath>

namespace semnav
{
namespace
{
using O = SweepObstacles::TOptions;
const OptionTable<O>& optionTable()
{
	static const auto t =
	    OptionTable<O>()
	        .real(
	            "min_height_m", &O::minHeight, -1, 10,
	            "Sweep points above this height...")
	        .real(
	            "max_height_m", &O::maxHeight, 0, 10,
	            "...and below this one (the robot's top) are obstacles.")
	        .real(
	            "max_range_m", &O::maxRange, 0.1, 100,
	            "Farther points are ignored.")
	        .real(
	            "max_age_s", &O::maxAge, 0.1, 1e5,
	            "Older obstacles count as blocked: the navigator stops.")
	        .real(
	            "cell_m", &O::cell, 0.005, 1,
	            "Points are thinned to one per cell of this size.");
	return t;
}
}  // namespace

SEMNAV_OPTIONS_FROM_TABLE(SweepObstacles::TOptions, optionTable())

SweepObstacles::SweepObstacles(const RobotBase& base, const TOptions& options)
    : m_base(base), m_options(options)
{
}

void SweepObstacles::update(const Sweep& sweep)
{
	const mrpt::poses::CPose2D at = sweep.odometry();
	const double r2 = m_options.maxRange * m_options.maxRange;
	std::lock_guard<std::mutex> lock(m_mutex);
	// Sweeps of one stop (the robot only turned on the spot between them,
	// as at a stop-and-scan start) add up: each sees 180 deg of it.
	const bool sameStop =
	    m_hasSweep &&
	    std::hypot(at.x() - m_at.x(), at.y() - m_at.y()) < m_options.cell;
	if (!sameStop)
	{
		m_points.clear();
		m_cells.clear();
	}
	for (const auto& p : sweep.points())
	{
		if (!std::isfinite(p.x) || p.z < m_options.minHeight ||
		    p.z > m_options.maxHeight || p.x * p.x + p.y * p.y > r2)
			continue;
		double x, y;
		at.composePoint(p.x, p.y, x, y);
		const auto key = std::make_tuple(
		    std::lround(x / m_options.cell), std::lround(y / m_options.cell),
		    std::lround(p.z / m_options.cell));
		if (m_cells.insert(key).second)
			m_points.push_back(
			    {static_cast<float>(x), static_cast<float>(y), p.z});
	}
	m_at = at;
	m_time = sweep.timestamp();
	m_hasSweep = true;
}

bool SweepObstacles::sense(
    mrpt::maps::CSimplePointsMap& robotFrame, mrpt::Clock::time_point& sensedAt)
{
	robotFrame.clear();
	const RobotBase::Odometry odo = m_base.odometry();
	std::lock_guard<std::mutex> lock(m_mutex);
	if (!m_hasSweep) return false;
	const double age =
	    mrpt::Clock::toDouble(odo.time) - mrpt::Clock::toDouble(m_time);
	if (age > m_options.maxAge) return false;
	sensedAt = m_time;
	const mrpt::poses::CPose2D now(odo.pose);
	for (const auto& p : m_points)
	{
		double x, y;
		now.inverseComposePoint(p.x, p.y, x, y);
		robotFrame.insertPoint(
		    static_cast<float>(x), static_cast<float>(y), p.z);
	}
	return true;
}

std::size_t SweepObstacles::size() const
{
	std::lock_guard<std::mutex> lock(m_mutex);
	return m_points.size();
}

}  // namespace semnav
