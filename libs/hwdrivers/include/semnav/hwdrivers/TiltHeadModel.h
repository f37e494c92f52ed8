/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <chrono>
#include <mutex>

namespace semnav
{
/** Motion of an emulated pan-tilt unit's tilt axis, in motor positions.
 *
 * The head moves toward its target at constant speed (no acceleration
 * ramp) and stops there. The physical angle is continuous; the position a
 * controller reports is the nearest step. Shared by the PTU emulator (which
 * commands it) and the LMS emulator (which scans at its angle).
 * Thread-safe. */
class TiltHeadModel
{
public:
	using Clock = std::chrono::steady_clock;

	/** `resolution` rad per position; limits in positions. */
	TiltHeadModel(double resolution, long minPos, long maxPos);

	double resolution() const { return m_res; }
	long minPosition() const { return m_min; }
	long maxPosition() const { return m_max; }

	/** Exact (continuous) position at t. */
	double exactPosition(Clock::time_point t) const;
	/** Reported position at t (nearest step). */
	long position(Clock::time_point t) const;
	/** Physical tilt at t, rad. */
	double angle(Clock::time_point t) const;

	/** New target (clamped to the limits by the caller). */
	void moveTo(long target, Clock::time_point t);
	void halt(Clock::time_point t);
	long target() const;
	/** Speed, positions per second (> 0). */
	void setSpeed(double posPerSec, Clock::time_point t);
	double speed() const;
	bool moving(Clock::time_point t) const;

private:
	double exactLocked(Clock::time_point t) const;

	mutable std::mutex m_mtx;
	double m_res;
	long m_min, m_max;
	Clock::time_point m_tRef{};
	double m_posRef = 0;
	long m_target = 0;
	double m_speed = 1000;
};

}  // namespace semnav
