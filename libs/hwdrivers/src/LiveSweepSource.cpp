/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/core/bits_math.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <semnav/common/Error.h>
#include <semnav/common/OptionTable.h>
#include <semnav/hwdrivers/LiveSweepSource.h>
#include <semnav/scan/RawlogWriter.h>

#include <algorithm>
#include <chrono>
#include <cstdio>

namespace semnav
{
namespace
{
using Clock = mrpt::Clock;

double secondsBetween(Clock::time_point a, Clock::time_point b)
{
	return std::chrono::duration<double>(b - a).count();
}

Clock::duration seconds(double s)
{
	return std::chrono::duration_cast<Clock::duration>(
	    std::chrono::duration<double>(s));
}

using O = LiveSweepSource::TOptions;
const OptionTable<O>& optionTable()
{
	static const auto t =
	    OptionTable<O>()
	        .real(
	            "device_lost_after_s", &O::deviceLostAfter, 0, 3600,
	            "No scan line for this long: the source ends (device lost); "
	            "0: a fault's recovery + 10 s.")
	        .text(
	            "record_rawlog", &O::recordPath,
	            "Rawlog recording every line and odometry reading; empty: "
	            "none.")
	        .flag(
	            "record_streaming", &O::recordStreaming,
	            "Write the recording straight to its path, flushed line by "
	            "line (it survives the process being killed); false: a "
	            "temporary file renamed at the end.");
	return t;
}

/** Automatic device_lost_after_s: this much beyond a fault's recovery
 * (MRPT's laser setup alone may take 5 s). */
constexpr double kLostMargin = 10.0;

/** Shortest silence a fault of the sensor can cause before lines flow
 * again: the stall detection, one reconnection attempt and the head's way
 * back to the start of the cut sweep, unrecorded (s). */
double faultRecoveryTime(const CTiltingLMS2xx::TOptions& o)
{
	return o.stallTimeout + o.reconnectDelay +
	       (o.thetaMax - o.thetaMin) / o.tiltSpeed;
}
}  // namespace

SEMNAV_OPTIONS_FROM_TABLE(LiveSweepSource::TOptions, optionTable())

LiveSweepSource::LiveSweepSource(
    const mrpt::config::CConfigFileBase& config, const std::string& section,
    const TOptions& options, OdometryProvider odometry)
    : mrpt::system::COutputLogger("LiveSweepSource"),
      m_sensor(std::make_unique<CTiltingLMS2xx>()),
      m_options(options),
      m_assemblerOptions(options.assembler),
      m_odometry(std::move(odometry))
{
	m_sensor->loadConfig(config, section);
	const auto& so = m_sensor->options();
	if (!(m_sensor->getProcessRate() > 0))
		throw ConfigError("[" + section + "] process_rate must be > 0");
	if (m_options.deviceLostAfter <= 0)
		m_options.deviceLostAfter = faultRecoveryTime(so) + kLostMargin;
	else if (m_options.deviceLostAfter <= faultRecoveryTime(so))
	{
		char msg[200];
		std::snprintf(
		    msg, sizeof(msg),
		    "device_lost_after_s = %.3g is not longer than a fault's "
		    "recovery in [%s] (stall_timeout_s + reconnect_delay_s + one "
		    "sweep = %.3g s)",
		    m_options.deviceLostAfter, section.c_str(), faultRecoveryTime(so));
		throw ConfigError(msg);
	}
	if (m_assemblerOptions.nominalSpan <= 0)
		m_assemblerOptions.nominalSpan = so.thetaMax - so.thetaMin;
	if (m_assemblerOptions.sensorLabel.empty())
		m_assemblerOptions.sensorLabel = m_sensor->getSensorLabel();
	m_assembler.emplace(m_assemblerOptions);
	// Routine losses (a few lines, sweeps cut by motion) stay out of the
	// robot's console.
	m_assembler->setMinLoggingLevel(mrpt::system::LVL_WARN);
	// A line can leave the sensor up to max_tilt_wait_s after it was taken
	// (waiting for the head's position), plus its telegram and a cycle.
	m_odometryHold = so.maxTiltWait + 1.0 / m_sensor->lineRateLimit() +
	                 2.0 / m_sensor->getProcessRate();
	if (!m_options.recordPath.empty())
		m_writer = std::make_unique<RawlogWriter>(
		    m_options.recordPath, 1,
		    m_options.recordStreaming ? RawlogWriter::Mode::Streaming
		                              : RawlogWriter::Mode::Atomic);
	m_sensor->initialize();
	m_thread = std::thread([this] { run(); });
}

LiveSweepSource::LiveSweepSource(
    const mrpt::config::CConfigFileBase& config, const std::string& section)
    : LiveSweepSource(config, section, TOptions())
{
}

LiveSweepSource::~LiveSweepSource()
{
	try
	{
		stop();
	}
	catch (const std::exception& e)
	{
		MRPT_LOG_ERROR_FMT("stopping: %s", e.what());
	}
}

const CTiltingLMS2xx::TOptions& LiveSweepSource::sensorOptions() const
{
	return m_sensor->options();
}

CTiltingLMS2xx::Stats LiveSweepSource::sensorStats() const
{
	return m_sensor->stats();
}

void LiveSweepSource::stop()
{
	{
		std::lock_guard<std::mutex> lk(m_mtx);
		if (m_stopped) return;
		m_stopped = true;
	}
	cancel();
	if (m_thread.joinable()) m_thread.join();
	if (m_writer) m_writer->commit();
}

void LiveSweepSource::cancel()
{
	{
		std::lock_guard<std::mutex> lk(m_mtx);
		if (m_end == End::None)
		{
			m_end = End::Cancelled;
			m_endMessage = "cancelled";
		}
	}
	m_stopThread = true;
	m_cv.notify_all();
}

SweepSource::End LiveSweepSource::end() const
{
	std::lock_guard<std::mutex> lk(m_mtx);
	// DeviceLost and stop() end only once the queue is empty.
	return m_end == End::Cancelled || m_ready.empty() ? m_end : End::None;
}

std::string LiveSweepSource::endMessage() const
{
	std::lock_guard<std::mutex> lk(m_mtx);
	if (m_end == End::None) return "";
	return m_sensor->options().lmsPort + ": " + endName(m_end) + " after " +
	       std::to_string(m_returned) + " complete sweeps (" +
	       std::to_string(m_skipped) + " incomplete skipped): " + m_endMessage;
}

bool LiveSweepSource::next(Sweep& sweep, mrpt::Clock::time_point notBefore)
{
	std::unique_lock<std::mutex> lk(m_mtx);
	for (;;)
	{
		if (m_end == End::Cancelled) return false;
		while (!m_ready.empty())
		{
			Sweep s = std::move(m_ready.front());
			m_ready.pop_front();
			if (s.timestamp() < notBefore) continue;
			m_returned++;
			sweep = std::move(s);
			return true;
		}
		if (m_end != End::None) return false;
		m_cv.wait(lk);
	}
}

void LiveSweepSource::endWith(End why, const std::string& message)
{
	{
		std::lock_guard<std::mutex> lk(m_mtx);
		if (m_end != End::None) return;
		m_end = why;
		m_endMessage = message;
	}
	MRPT_LOG_ERROR_FMT("%s", endMessage().c_str());
	m_cv.notify_all();
}

void LiveSweepSource::feed(const mrpt::obs::CObservation::Ptr& obs)
{
	if (m_writer)
	{
		try
		{
			m_writer->write(*obs);
		}
		catch (const IoError& e)
		{
			// Keep what was recorded; the sweeps go on.
			MRPT_LOG_ERROR_FMT("recording stopped: %s", e.what());
			m_writer->commit();
			m_writer.reset();
		}
	}
	m_assembler->push(obs);
}

void LiveSweepSource::pollOdometry()
{
	OdometryReading r;
	if (m_odometry)
	{
		try
		{
			r = m_odometry();
		}
		catch (const std::exception& e)
		{
			MRPT_LOG_THROTTLE_WARN_FMT(
			    5.0, "odometry provider failed: %s", e.what());
			return;
		}
	}
	else if (m_odometryReadings > 0)
		return;  // the origin, once
	const bool stamped = r.timestamp != Clock::time_point{};
	if (m_odometryReadings > 0 && stamped && r.timestamp == m_lastProvidedTime)
		return;  // not a new reading
	m_lastProvidedTime = r.timestamp;
	// Not after it was polled (a reading "from the future", another clock,
	// would wait for a line taken after it), and in time order.
	const auto now = Clock::now();
	auto t = stamped && r.timestamp < now ? r.timestamp : now;
	if (m_odometryReadings > 0) t = std::max(t, m_lastOdometryTime);
	m_lastOdometryTime = r.timestamp = t;
	auto odo = mrpt::obs::CObservationOdometry::Create();
	odo->sensorLabel = "ODOMETRY";
	odo->timestamp = r.timestamp;
	odo->odometry = r.pose;
	m_odometryReadings++;
	m_pendingOdometry.push_back(odo);
}

void LiveSweepSource::flushOdometry(Clock::time_point t)
{
	while (!m_pendingOdometry.empty() &&
	       m_pendingOdometry.front()->timestamp <= t)
	{
		feed(m_pendingOdometry.front());
		m_pendingOdometry.pop_front();
	}
}

void LiveSweepSource::queueSweeps()
{
	bool added = false;
	while (m_assembler->hasSweep())
	{
		Sweep s = m_assembler->pop();
		if (!s.quality().complete)
		{
			m_skipped++;
			continue;
		}
		std::lock_guard<std::mutex> lk(m_mtx);
		if (m_ready.size() >= kMaxQueued)
		{
			m_ready.pop_front();
			m_dropped++;
		}
		m_ready.push_back(std::move(s));
		added = true;
	}
	if (added) m_cv.notify_all();
}

void LiveSweepSource::run()
{
	const double period = 1.0 / m_sensor->getProcessRate();
	auto lastLine = Clock::now();
	// The first reading comes before any line: the first sweep has one.
	pollOdometry();
	flushOdometry(Clock::time_point::max());
	while (!m_stopThread)
	{
		const auto t0 = Clock::now();
		try
		{
			m_sensor->doProcess();
		}
		catch (const std::exception& e)
		{
			MRPT_LOG_THROTTLE_ERROR_FMT(5.0, "doProcess: %s", e.what());
		}
		pollOdometry();
		mrpt::hwdrivers::CGenericSensor::TListObservations observations;
		m_sensor->getObservations(observations);
		for (const auto& [t, obj] : observations)
		{
			auto scan =
			    std::dynamic_pointer_cast<mrpt::obs::CObservation2DRangeScan>(
			        obj);
			if (!scan) continue;
			flushOdometry(scan->timestamp);
			feed(scan);
			m_lines++;
			lastLine = Clock::now();
		}
		// No line taken before these readings can still come.
		flushOdometry(Clock::now() - seconds(m_odometryHold));
		queueSweeps();

		const double silent = secondsBetween(lastLine, Clock::now());
		if (silent > m_options.deviceLostAfter)
		{
			const auto s = m_sensor->stats();
			char msg[300];
			std::snprintf(
			    msg, sizeof(msg),
			    "no scan line for %.1f s (head %s; %zu faults, %zu "
			    "reconnects, %zu lines without a tilt)",
			    silent, m_sensor->options().ptuPort.c_str(), s.faults,
			    s.reconnects, s.linesNoTilt);
			// The cut sweep is counted (or returned, had it got to its end).
			flushOdometry(Clock::time_point::max());
			m_assembler->finish();
			queueSweeps();
			endWith(End::DeviceLost, msg);
			break;
		}
		const auto until = t0 + seconds(period);
		while (!m_stopThread && Clock::now() < until)
			std::this_thread::sleep_for(std::min(
			    until - Clock::now(),
			    Clock::duration(std::chrono::milliseconds(10))));
	}
	// Every reading into the recording.
	flushOdometry(Clock::time_point::max());
}

}  // namespace semnav
