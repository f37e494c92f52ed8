/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/core/Clock.h>
#include <mrpt/obs/CObservation.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/system/COutputLogger.h>
#include <semnav/hwdrivers/CTiltingLMS2xx.h>
#include <semnav/scan/SweepAssembler.h>
#include <semnav/scan/SweepSource.h>

#include <atomic>
#include <condition_variable>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

namespace semnav
{
class RawlogWriter;

/** The live tilting LMS2xx as a SweepSource: the project's CTiltingLMS2xx
 * run in-process, configured from the same INI section as for the
 * rawlog-grabber plugin (e.g. [TILT_LMS] of config/grabber-emulated.ini).
 *
 * The constructor loads the section and initializes the sensor as
 * rawlog-grabber does, then starts the source's own thread, which calls
 * doProcess() at the section's process_rate, drains the sensor's
 * observations and feeds the scan lines to a SweepAssembler. The odometry
 * provider (if any) is polled on that thread every cycle; each new reading
 * goes to the assembler as a CObservationOdometry, in time order with the
 * lines, so a sweep during which the robot moved ends incomplete
 * (SweepAssembler::TOptions::splitOnMotion) and each sweep carries the
 * odometry at its start. Without a provider the odometry is the origin.
 *
 * Complete sweeps wait in a queue (at most kMaxQueued; older ones are
 * dropped and counted) for next(); incomplete ones are skipped and counted.
 * Every line and odometry reading can be recorded to a rawlog as it
 * arrives (TOptions::recordPath); RawlogSweepSource over that file, with
 * assemblerOptions(), gives the same sweeps.
 *
 * Ends: Cancelled by cancel(); DeviceLost when no scan line has come out of
 * the sensor for TOptions::deviceLostAfter seconds (from the start or the
 * last line), whatever the cause: the laser stalled or unplugged and not
 * back (CTiltingLMS2xx keeps reopening it), or the head not answering (no
 * tilt for the lines). Sweeps completed before the loss are still returned
 * first. endMessage() names the ports and the sensor's fault counters. */
class LiveSweepSource : public SweepSource, public mrpt::system::COutputLogger
{
public:
	/** The source's own keys (not the sensor's). */
	struct TOptions : public mrpt::config::CLoadableOptions
	{
		void loadFromConfigFile(
		    const mrpt::config::CConfigFileBase& c,
		    const std::string& section) override;
		void saveToConfigFile(
		    mrpt::config::CConfigFileBase& c,
		    const std::string& section) const override;

		/** No scan line for this long ends the source with DeviceLost (s).
		 * Must exceed one fault's recovery by the sensor: stall_timeout_s +
		 * reconnect_delay_s + one sweep's time (the head goes back to the
		 * start of the cut sweep without recording). 0: that + 10 s. */
		double deviceLostAfter = 0;
		/** Rawlog recording every line and odometry reading; empty = none.
		 * Written to a temporary file, renamed at stop() (or streamed). */
		std::string recordPath;
		/** record_streaming: the recording goes straight to recordPath,
		 * flushed line by line (RawlogWriter::Mode::Streaming). */
		bool recordStreaming = false;
		/** How lines become sweeps; nominalSpan = 0 takes the sensor's
		 * theta_max_deg - theta_min_deg. */
		SweepAssembler::TOptions assembler;
	};

	/** One odometry reading, stamped in this machine's mrpt::Clock time. A
	 * reading is new when its time differs from the previous one's; a zero
	 * time makes every poll a reading, stamped when polled (as is a time
	 * in the future). */
	struct OdometryReading
	{
		mrpt::poses::CPose2D pose;
		mrpt::Clock::time_point timestamp{};
	};
	/** Called on the source's thread every cycle; must not block long. */
	using OdometryProvider = std::function<OdometryReading()>;

	/** Sweeps kept for next() at most. */
	static constexpr std::size_t kMaxQueued = 16;

	/** Loads [section] of `config` into a CTiltingLMS2xx (ConfigError
	 * naming the key when bad), opens the recording (IoError), initializes
	 * the sensor (Error when the head cannot be opened) and starts. */
	LiveSweepSource(
	    const mrpt::config::CConfigFileBase& config, const std::string& section,
	    const TOptions& options,
	    OdometryProvider odometry = OdometryProvider());
	/** With the default TOptions and no odometry provider. */
	LiveSweepSource(
	    const mrpt::config::CConfigFileBase& config,
	    const std::string& section);
	/** stop(); the sensor closes its ports. */
	~LiveSweepSource() override;
	LiveSweepSource(const LiveSweepSource&) = delete;
	LiveSweepSource& operator=(const LiveSweepSource&) = delete;

	bool next(Sweep& sweep, mrpt::Clock::time_point notBefore = {}) override;
	void cancel() override;
	End end() const override;
	std::string endMessage() const override;

	/** cancel(), then waits for the thread and commits the recording.
	 * Idempotent. */
	void stop();

	/** The assembler's options in use (nominal span filled in): read the
	 * recording back with these. */
	const SweepAssembler::TOptions& assemblerOptions() const
	{
		return m_assemblerOptions;
	}
	const CTiltingLMS2xx::TOptions& sensorOptions() const;
	/** The silence (s) after which the source ends with DeviceLost. */
	double deviceLostAfter() const { return m_options.deviceLostAfter; }
	/** The sensor's counters (faults, reconnects, ...). */
	CTiltingLMS2xx::Stats sensorStats() const;

	std::size_t linesReceived() const { return m_lines; }
	std::size_t odometryReadings() const { return m_odometryReadings; }
	/** Incomplete sweeps skipped so far. */
	std::size_t skippedIncomplete() const { return m_skipped; }
	/** Complete sweeps dropped because the queue was full. */
	std::size_t droppedSweeps() const { return m_dropped; }

private:
	void run();
	/** Polls the provider; a new reading joins m_pendingOdometry. */
	void pollOdometry();
	/** Feeds readings taken before `t` to the assembler. */
	void flushOdometry(mrpt::Clock::time_point t);
	/** Records `obs` and pushes it to the assembler. */
	void feed(const mrpt::obs::CObservation::Ptr& obs);
	/** Moves the assembler's sweeps to the queue. */
	void queueSweeps();
	void endWith(End why, const std::string& message);

	std::unique_ptr<CTiltingLMS2xx> m_sensor;
	TOptions m_options;
	SweepAssembler::TOptions m_assemblerOptions;
	OdometryProvider m_odometry;
	std::unique_ptr<RawlogWriter> m_writer;

	// Owned by the source's thread.
	std::optional<SweepAssembler> m_assembler;
	std::deque<mrpt::obs::CObservation::Ptr> m_pendingOdometry;
	mrpt::Clock::time_point m_lastOdometryTime{}, m_lastProvidedTime{};
	double m_odometryHold = 0;

	std::thread m_thread;
	std::atomic<bool> m_stopThread{false};
	std::atomic<std::size_t> m_lines{0}, m_odometryReadings{0};
	std::atomic<std::size_t> m_skipped{0}, m_dropped{0};

	mutable std::mutex m_mtx;  // guards the members below
	std::condition_variable m_cv;
	std::deque<Sweep> m_ready;
	End m_end = End::None;
	std::string m_endMessage;
	std::size_t m_returned = 0;
	bool m_stopped = false;
};

}  // namespace semnav
