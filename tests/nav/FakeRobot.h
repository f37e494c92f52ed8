/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

// A fake robot base and clock for the navigation tests: ideal
// differential-drive kinematics, a watchdog, and a log of every call, with
// no simulator behind them (tests/nav links semnav::nav only).

#include <mrpt/core/Clock.h>
#include <mrpt/math/TPose2D.h>
#include <mrpt/math/wrap2pi.h>
#include <mrpt/poses/CPose2D.h>
#include <semnav/robot/ControlClock.h>
#include <semnav/robot/PoseSource.h>
#include <semnav/robot/RobotBase.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace semnav::test
{
/** Fake time t as an MRPT timestamp (t = 0 at 2020-01-01). */
inline mrpt::Clock::time_point fakeTimestamp(double t)
{
	return mrpt::Clock::fromDouble(1577836800.0 + t);
}

/** A differential-drive base that moves exactly as commanded (the true
 * pose) and records every call. Its odometry starts at (0, 0, 0) wherever
 * the robot truly stands (the odometry frame is not the map frame) and may
 * drift in heading by `headingDriftPerM` per metre travelled. Time passes
 * only through advance() (FakeClock). */
class FakeBase : public RobotBase
{
public:
	/** One call of the RobotBase interface, or a watchdog stop. */
	struct Call
	{
		enum class Kind
		{
			SetVelocity,
			KeepAlive,
			Stop,
			EmergencyStop,
			WatchdogStop
		};
		Kind kind;
		double time;
		double v = 0, w = 0;
		bool accepted = true;
	};

	FakeBase(
	    const mrpt::math::TPose2D& truePose, double watchdog,
	    double headingDriftPerM = 0)
	    : m_truth(truePose), m_watchdog(watchdog), m_drift(headingDriftPerM)
	{
	}

	bool setVelocity(double v, double w) override
	{
		const bool ok = !m_emergency;
		m_calls.push_back({Call::Kind::SetVelocity, m_time, v, w, ok});
		if (ok) command(v, w);
		return ok;
	}
	void keepAlive() override
	{
		m_calls.push_back({Call::Kind::KeepAlive, m_time});
		m_lastCommand = m_time;
	}
	bool stop() override
	{
		m_calls.push_back({Call::Kind::Stop, m_time});
		command(0, 0);
		return true;
	}
	bool emergencyStop() override
	{
		m_calls.push_back({Call::Kind::EmergencyStop, m_time});
		command(0, 0);
		m_emergency = true;
		return true;
	}
	void resetEmergencyStop() override { m_emergency = false; }
	bool emergencyStopped() const override { return m_emergency; }
	Odometry odometry() const override
	{
		Odometry o;
		o.pose = m_odometry;
		o.velocity = {m_v, 0, m_w};
		o.time = fakeTimestamp(m_time);
		o.distance = m_distance;
		return o;
	}
	double watchdogPeriod() const override { return m_watchdog; }

	/** Lets dt pass: enforces the watchdog, then moves along the arc of
	 * the current command. */
	void advance(double dt)
	{
		if (moving() && m_time - m_lastCommand > m_watchdog)
		{
			m_calls.push_back({Call::Kind::WatchdogStop, m_time});
			m_v = m_w = 0;
		}
		const mrpt::poses::CPose2D delta = arc(m_v, m_w, dt);
		const double d = std::abs(m_v) * dt;
		m_truth = (mrpt::poses::CPose2D(m_truth) + delta).asTPose();
		m_truth.phi = mrpt::math::wrapToPi(m_truth.phi);
		const mrpt::poses::CPose2D odoDelta(
		    delta.x(), delta.y(), delta.phi() + m_drift * d);
		m_odometry = (mrpt::poses::CPose2D(m_odometry) + odoDelta).asTPose();
		m_odometry.phi = mrpt::math::wrapToPi(m_odometry.phi);
		m_distance += d;
		m_time += dt;
	}

	/** The robot is carried to `pose` (the odometry notices nothing). */
	void carryTo(const mrpt::math::TPose2D& pose) { m_truth = pose; }
	const mrpt::math::TPose2D& truePose() const { return m_truth; }
	double time() const { return m_time; }
	/** The command in force (zero after a stop or the watchdog). */
	bool moving() const { return m_v != 0 || m_w != 0; }
	const std::vector<Call>& calls() const { return m_calls; }

private:
	/** Motion of the robot frame in dt at (v, w). */
	static mrpt::poses::CPose2D arc(double v, double w, double dt)
	{
		const double a = w * dt;
		if (std::abs(a) < 1e-9) return {v * dt, 0, a};
		const double r = v / w;
		return {r * std::sin(a), r * (1 - std::cos(a)), a};
	}
	void command(double v, double w)
	{
		m_v = v;
		m_w = w;
		m_lastCommand = m_time;
	}

	mrpt::math::TPose2D m_truth;
	mrpt::math::TPose2D m_odometry{0, 0, 0};
	double m_watchdog, m_drift;
	double m_time = 0, m_lastCommand = 0, m_distance = 0;
	double m_v = 0, m_w = 0;
	bool m_emergency = false;
	std::vector<Call> m_calls;
};

/** The fake base's time: waitFor() advances the base in steps of at most
 * one period. While it exists MRPT's clock (mrpt::Clock, Simulated source)
 * follows it, as it must for any clock that is not wall time: MRPT's
 * navigator and StopAndScanLocalizer's "sweep begun now" read
 * mrpt::Clock::now(). */
class FakeClock : public ControlClock
{
public:
	FakeClock(FakeBase& base, double period)
	    : m_base(base),
	      m_period(period),
	      m_previous(mrpt::Clock::getActiveClock()),
	      m_previousTime(mrpt::Clock::now())
	{
		mrpt::Clock::setSimulatedTime(fakeTimestamp(m_base.time()));
		mrpt::Clock::setActiveClock(mrpt::Clock::Simulated);
	}
	/** MRPT's clock returns to its source and time before this clock. */
	~FakeClock() override
	{
		if (m_previous == mrpt::Clock::Simulated)
			mrpt::Clock::setSimulatedTime(m_previousTime);
		mrpt::Clock::setActiveClock(m_previous);
	}
	FakeClock(const FakeClock&) = delete;
	FakeClock& operator=(const FakeClock&) = delete;

	double now() const override { return m_base.time(); }
	void waitFor(double seconds) override
	{
		for (double left = seconds; left > 1e-12; left -= m_period)
			m_base.advance(std::min(left, m_period));
		mrpt::Clock::setSimulatedTime(fakeTimestamp(m_base.time()));
	}
	double period() const override { return m_period; }

private:
	FakeBase& m_base;
	double m_period;
	mrpt::Clock::Source m_previous;
	mrpt::Clock::time_point m_previousTime;
};

/** The fake base's true pose (ground truth for the localizer's records). */
class FakeTruth : public PoseSource
{
public:
	explicit FakeTruth(const FakeBase& base) : m_base(base) {}
	mrpt::math::TPose2D pose() const override { return m_base.truePose(); }

private:
	const FakeBase& m_base;
};

}  // namespace semnav::test
