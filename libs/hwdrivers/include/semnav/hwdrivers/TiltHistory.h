/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/core/Clock.h>

#include <cstddef>
#include <deque>
#include <mutex>
#include <optional>

namespace semnav
{
/** Tilt positions reported by a pan-tilt unit, with their times, and the
 * tilt at any time between two reports (linear interpolation).
 *
 * Each sample carries `recording`: false while the head is being moved
 * outside a sweep (e.g. back to the start after a fault); a time between
 * two samples of which one is not recording has no tilt. Thread-safe. */
class TiltHistory
{
public:
	struct Sample
	{
		mrpt::Clock::time_point t;
		double theta = 0;  ///< rad, positive up
		bool recording = true;
	};
	/** Result of tiltAt(). */
	enum class Lookup
	{
		Ok,
		NotYet,  ///< no sample at or after t yet: ask again later
		TooOld,  ///< t is before the oldest sample kept
		NotRecording,
		/** The samples around t are further apart than maxGap: the head
		 * may have turned between them. */
		Gap
	};

	/** Keeps samples for `keepSeconds`; interpolates only between samples
	 * at most `maxGapSeconds` apart. */
	explicit TiltHistory(double keepSeconds = 10.0, double maxGapSeconds = 1e9)
	    : m_keep(keepSeconds), m_maxGap(maxGapSeconds)
	{
	}

	/** Appends a sample; samples must come in time order (older ones are
	 * ignored). */
	void add(const Sample& s);
	/** Tilt at time t (rad). */
	Lookup tiltAt(mrpt::Clock::time_point t, double& theta) const;
	/** Latest sample, if any. */
	std::optional<Sample> latest() const;
	std::size_t size() const;
	void clear();

private:
	mutable std::mutex m_mtx;
	std::deque<Sample> m_samples;
	double m_keep, m_maxGap;
};

}  // namespace semnav
