/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/scan/SweepSource.h>
#include <semnav/sim/TiltingLaserSimulator.h>

#include <atomic>
#include <cstdint>

namespace semnav
{
class SimulatedBase;
class RawlogWriter;
class ControlClock;

/** Sweeps of the simulated tilting LMS200 (TiltingLaserSimulator) taken
 * where the simulated base truly stands, as a SweepSource. Each next()
 * takes one sweep: its lines are stamped from the simulated time on, the
 * clock advances by lines x line_period_s while the head nods (the robot
 * keeps its last command: stop it first), and the sweep carries the
 * odometry at its end. It ends only by cancel(). A sweep during which
 * the robot moved throws Error (the caller must stop the robot first, as
 * stop-and-scan does). */
class SimulatedSweepSource : public SweepSource
{
public:
	/** `base` and `clock` (which advances it) must outlive the source;
	 * `seed` seeds the range noise. */
	SimulatedSweepSource(
	    SimulatedBase& base, ControlClock& clock, const SensorSpec& sensor,
	    uint64_t seed, double linePeriod);

	bool next(Sweep& sweep, mrpt::Clock::time_point notBefore = {}) override;
	void cancel() override { m_cancelled = true; }
	End end() const override { return m_end; }
	std::string endMessage() const override { return m_message; }

	/** Records every sweep from now on into `rawlog` as semnav-sim writes
	 * its sweeps (an odometry reading, then the scan lines), so that
	 * semnav-map can rebuild the map of a run; nullptr stops. `rawlog`
	 * must outlive the recording. */
	void record(RawlogWriter* rawlog) { m_rawlog = rawlog; }

	/** Sweeps taken so far. */
	std::size_t sweeps() const { return m_index; }
	const TiltingLaserSimulator& laser() const { return m_laser; }

private:
	SimulatedBase& m_base;
	ControlClock& m_clock;
	TiltingLaserSimulator m_laser;
	double m_linePeriod;
	std::size_t m_index = 0;
	std::atomic<bool> m_cancelled{false};
	RawlogWriter* m_rawlog = nullptr;
	End m_end = End::None;
	std::string m_message;
};

}  // namespace semnav
