/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/system/datetime.h>
#include <semnav/hwdrivers/TiltHistory.h>

#include <algorithm>
#include <chrono>

namespace semnav
{
namespace
{
/** b - a in seconds (any time points, unlike timeDifference()). */
inline double secondsBetween(
    mrpt::Clock::time_point a, mrpt::Clock::time_point b)
{
	return std::chrono::duration<double>(b - a).count();
}
}  // namespace

void TiltHistory::add(const Sample& s)
{
	std::lock_guard<std::mutex> lk(m_mtx);
	if (!m_samples.empty() && s.t < m_samples.back().t) return;
	m_samples.push_back(s);
	while (m_samples.size() > 2 &&
	       secondsBetween(m_samples.front().t, s.t) > m_keep)
		m_samples.pop_front();
}

TiltHistory::Lookup TiltHistory::tiltAt(
    mrpt::Clock::time_point t, double& theta) const
{
	std::lock_guard<std::mutex> lk(m_mtx);
	if (m_samples.empty() || m_samples.back().t < t) return Lookup::NotYet;
	if (t < m_samples.front().t) return Lookup::TooOld;
	// First sample at or after t.
	const auto it = std::lower_bound(
	    m_samples.begin(), m_samples.end(), t,
	    [](const Sample& s, mrpt::Clock::time_point tt) { return s.t < tt; });
	if (it->t == t)
	{
		if (!it->recording) return Lookup::NotRecording;
		theta = it->theta;
		return Lookup::Ok;
	}
	const auto prev = std::prev(it);
	if (!prev->recording || !it->recording) return Lookup::NotRecording;
	const double span = secondsBetween(prev->t, it->t);
	if (span > m_maxGap) return Lookup::Gap;
	const double a = span > 0 ? secondsBetween(prev->t, t) / span : 0;
	theta = prev->theta + a * (it->theta - prev->theta);
	return Lookup::Ok;
}

std::optional<TiltHistory::Sample> TiltHistory::latest() const
{
	std::lock_guard<std::mutex> lk(m_mtx);
	if (m_samples.empty()) return std::nullopt;
	return m_samples.back();
}

std::size_t TiltHistory::size() const
{
	std::lock_guard<std::mutex> lk(m_mtx);
	return m_samples.size();
}

void TiltHistory::clear()
{
	std::lock_guard<std::mutex> lk(m_mtx);
	m_samples.clear();
}

}  // namespace semnav
