/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/hwdrivers/TiltHeadModel.h>

#include <cmath>

namespace semnav
{
TiltHeadModel::TiltHeadModel(double resolution, long minPos, long maxPos)
    : m_res(resolution), m_min(minPos), m_max(maxPos), m_tRef(Clock::now())
{
}

double TiltHeadModel::exactLocked(Clock::time_point t) const
{
	const double dt =
	    std::max(0.0, std::chrono::duration<double>(t - m_tRef).count());
	const double d = m_target - m_posRef;
	const double step = m_speed * dt;
	if (std::abs(d) <= step) return m_target;
	return m_posRef + (d > 0 ? step : -step);
}

double TiltHeadModel::exactPosition(Clock::time_point t) const
{
	std::lock_guard<std::mutex> lk(m_mtx);
	return exactLocked(t);
}

long TiltHeadModel::position(Clock::time_point t) const
{
	return std::lround(exactPosition(t));
}

double TiltHeadModel::angle(Clock::time_point t) const
{
	return exactPosition(t) * m_res;
}

void TiltHeadModel::moveTo(long target, Clock::time_point t)
{
	std::lock_guard<std::mutex> lk(m_mtx);
	m_posRef = exactLocked(t);
	m_tRef = t;
	m_target = target;
}

void TiltHeadModel::halt(Clock::time_point t)
{
	std::lock_guard<std::mutex> lk(m_mtx);
	m_posRef = exactLocked(t);
	m_tRef = t;
	m_target = std::lround(m_posRef);
}

long TiltHeadModel::target() const
{
	std::lock_guard<std::mutex> lk(m_mtx);
	return m_target;
}

void TiltHeadModel::setSpeed(double posPerSec, Clock::time_point t)
{
	std::lock_guard<std::mutex> lk(m_mtx);
	m_posRef = exactLocked(t);
	m_tRef = t;
	if (posPerSec > 0) m_speed = posPerSec;
}

double TiltHeadModel::speed() const
{
	std::lock_guard<std::mutex> lk(m_mtx);
	return m_speed;
}

bool TiltHeadModel::moving(Clock::time_point t) const
{
	std::lock_guard<std::mutex> lk(m_mtx);
	return exactLocked(t) != m_target;
}

}  // namespace semnav
