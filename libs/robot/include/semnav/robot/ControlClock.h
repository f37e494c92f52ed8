/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

namespace semnav
{
/** The time a control loop runs on: real time on a robot (RealTimeClock,
 * waitFor() sleeps) or a simulation's time (waitFor() advances the
 * simulated world). Timestamps (odometry, sweeps, MRPT's navigator) use
 * mrpt::Clock: a clock that is not wall time must drive it (as
 * SimulatedBase does with mrpt::Clock's Simulated source). */
class ControlClock
{
public:
	virtual ~ControlClock() = default;
	/** Seconds since an arbitrary origin (monotonic). */
	virtual double now() const = 0;
	/** Lets `seconds` pass. */
	virtual void waitFor(double seconds) = 0;
	/** The control period: one step of a control loop (s). */
	virtual double period() const = 0;
	/** waitFor(period()). */
	void tick() { waitFor(period()); }
};

/** Wall time: std::chrono::steady_clock; waitFor() sleeps. */
class RealTimeClock : public ControlClock
{
public:
	/** `period`: the control period (s). */
	explicit RealTimeClock(double period) : m_period(period) {}
	double now() const override;
	void waitFor(double seconds) override;
	double period() const override { return m_period; }

private:
	double m_period;
};

}  // namespace semnav
