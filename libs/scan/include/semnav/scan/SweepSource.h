/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/core/Clock.h>
#include <semnav/scan/Sweep.h>

#include <string>

namespace semnav
{
/** Where complete sweeps come from: a rawlog file (RawlogSweepSource), the
 * simulator (SimulatedSweepSource, semnav::sim) or the live tilting LMS2xx
 * (LiveSweepSource, semnav::hwdrivers). One of the two seams between
 * semnav's runtime and a robot (the other is RobotBase).
 *
 * next() blocks until a complete sweep is there and returns it with the
 * robot's odometry during it (Sweep::odometry()). Incomplete sweeps
 * (interrupted, or the robot moved during them) are not returned.
 * When a source ends, next() returns false and end() says why. */
class SweepSource
{
public:
	enum class End
	{
		/** Not ended. */
		None,
		/** The rawlog (or the simulated run) has no more sweeps. */
		EndOfLog,
		/** The device stopped answering and could not be reopened. */
		DeviceLost,
		/** cancel() was called. */
		Cancelled
	};

	virtual ~SweepSource() = default;

	/** The next complete sweep whose first line was taken at or after
	 * `notBefore` (mrpt::Clock time; the default takes the next one).
	 * Stop-and-scan asks for the sweep begun after the robot stopped:
	 * together with SweepAssembler ending a sweep when the odometry moves,
	 * that is the next complete sweep taken while the robot stood still.
	 * Returns false when the source ended (see end()). */
	virtual bool next(Sweep& sweep, mrpt::Clock::time_point notBefore = {}) = 0;

	/** Makes a waiting or later next() return false with End::Cancelled;
	 * callable from any thread. */
	virtual void cancel() = 0;

	/** Why next() returned false (End::None while it has not). */
	virtual End end() const = 0;
	/** One line on how it ended (file and position, device and fault). */
	virtual std::string endMessage() const = 0;

	/** "none", "end of log", "device lost", "cancelled". */
	static const char* endName(End e);
};

}  // namespace semnav
