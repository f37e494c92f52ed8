/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/math/wrap2pi.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <semnav/common/Error.h>
#include <semnav/robot/ControlClock.h>
#include <semnav/scan/RawlogWriter.h>
#include <semnav/sim/SimulatedBase.h>
#include <semnav/sim/SimulatedSweepSource.h>

#include <cmath>

namespace semnav
{
SimulatedSweepSource::SimulatedSweepSource(
    SimulatedBase& base, ControlClock& clock, const SensorSpec& sensor,
    uint64_t seed, double linePeriod)
    : m_base(base),
      m_clock(clock),
      m_laser(base.caster(), sensor, seed),
      m_linePeriod(linePeriod)
{
}

bool SimulatedSweepSource::next(
    Sweep& sweep, mrpt::Clock::time_point /*notBefore: always met*/)
{
	if (m_cancelled)
	{
		m_end = End::Cancelled;
		m_message = "simulated laser: cancelled after " +
		            std::to_string(m_index) + " sweeps";
		return false;
	}
	const mrpt::math::TPose2D before = m_base.pose();
	const SimulatedSweep sim = m_laser.simulate(
	    m_base.pose(), m_index, SimulatedBase::timestampOf(m_base.time()),
	    m_linePeriod);
	// The robot stands still while the head nods.
	const double sweepTime =
	    m_linePeriod * static_cast<double>(m_laser.lineCount());
	if (sweepTime > 0) m_clock.waitFor(sweepTime);
	const mrpt::math::TPose2D after = m_base.pose();
	if (std::hypot(after.x - before.x, after.y - before.y) > 1e-3 ||
	    std::abs(mrpt::math::wrapToPi(after.phi - before.phi)) > 1e-3)
		throw Error(
		    "simulated laser: the robot moved during sweep " +
		    std::to_string(m_index) + " (stop it before sweeping)");
	sweep = sim.toSweep();
	sweep.setOdometry(mrpt::poses::CPose2D(m_base.odometry().pose));
	if (m_rawlog)
	{
		mrpt::obs::CObservationOdometry o;
		o.sensorLabel = "ODOMETRY";
		o.timestamp =
		    sim.lines.empty() ? sweep.timestamp() : sim.lines.front().timestamp;
		o.odometry = sweep.odometry();
		m_rawlog->write(o);
		for (const auto& line : sim.lines) m_rawlog->write(line);
	}
	m_index++;
	return true;
}

}  // namespace semnav
