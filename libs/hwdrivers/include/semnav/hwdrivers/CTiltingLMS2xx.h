/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/hwdrivers/CGenericSensor.h>
#include <mrpt/math/TPoint3D.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/system/COutputLogger.h>
#include <semnav/hwdrivers/TiltHistory.h>

#include <atomic>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

namespace mrpt::hwdrivers
{
class CSickLaserSerial;
class CPtuBase;
}  // namespace mrpt::hwdrivers

namespace semnav
{
class MonitoredSerialPort;

/** A SICK LMS2xx on a nodding pan-tilt unit, as one rawlog-grabber sensor
 * (`driver = CTiltingLMS2xx`, loaded from libsemnav_hwdrivers.so).
 *
 * The laser is driven by MRPT's CSickLaserSerial (baud-rate detection and
 * change, mm mode, 0.5 deg, continuous output) and the head by an MRPT
 * CPtuBase driver (CPtuDPerception by default), which nods between
 * theta_min and theta_max at tilt_speed. Three threads: the laser reader
 * (timestamps each scan line at its acquisition, i.e. arrival minus the
 * telegram's transmission time), the head controller (commands the nodding
 * and polls the position), and rawlog-grabber's own thread, which calls
 * doProcess(): each line gets the tilt at its time, interpolated between
 * the head's reported positions, and becomes one CObservation2DRangeScan
 * with sensorPose = tiltedSensorPose(mount, theta) as semnav-sim writes it.
 *
 * Faults: a telegram with a bad CRC is dropped and counted; no scan for
 * stall_timeout_s (stall or disconnect) ends the sweep as incomplete, the
 * laser is reopened (every reconnect_delay_s), the head goes back to the
 * start of the interrupted sweep without recording and a fresh sweep
 * starts once lines flow again. The interrupted sweep is closed by that
 * reversal, so SweepAssembler emits it with quality().complete == false. */
class CTiltingLMS2xx : public mrpt::system::COutputLogger,
                       public mrpt::hwdrivers::CGenericSensor
{
	DEFINE_GENERIC_SENSOR(CTiltingLMS2xx)

public:
	/** Sensor-specific keys of the sensor's INI section (the generic ones,
	 * driver / process_rate / max_queue_len / grab_decimation / sensorLabel,
	 * are CGenericSensor's). Unknown keys and out-of-range values throw
	 * ConfigError. */
	struct TOptions : public mrpt::config::CLoadableOptions
	{
		void loadFromConfigFile(
		    const mrpt::config::CConfigFileBase& c,
		    const std::string& section) override;
		void saveToConfigFile(
		    mrpt::config::CConfigFileBase& c,
		    const std::string& section) const override;

		/** Laser serial port (`COM_port_LIN`, MRPT's key). */
		std::string lmsPort;
		/** 9600, 38400 or 500000 (`COM_baudRate`). */
		int baudRate = 38400;
		/** LMS field of view (deg, 100 or 180) and resolution (1/100 deg:
		 * 25, 50 or 100). */
		int fovDeg = 180, resolutionCdeg = 50;
		/** Millimetre mode (8 m range, 1 mm units). */
		bool mmMode = true;
		/** `ptu_type`: dperception (CPtuDPerception) or tumicos (CTuMicos). */
		std::string ptuType = "dperception";
		std::string ptuPort;
		/** Head axis that tilts the laser: 'T' or 'P'. */
		char ptuAxis = 'T';
		/** theta = ptu_sign * head angle + ptu_offset. */
		double ptuSign = 1, ptuOffset = 0;
		/** Nodding range (rad) and speed (rad/s). */
		double thetaMin = -15 * M_PI / 180, thetaMax = 90 * M_PI / 180;
		double tiltSpeed = 18.75 * M_PI / 180;
		/** Head position polling period, s. */
		double ptuPollPeriod = 0.02;
		/** Tilt axis position in the robot frame (m). */
		mrpt::math::TPoint3D mount{0.0, 0.0, 0.45};
		/** Returns beyond this are "no return" (m); also the stored range of
		 * invalid beams, as semnav-sim writes them. */
		double maxRange = 8.0;
		/** Range noise std dev written as stdError (m). */
		double rangeNoise = 0.005;
		/** No scan for this long ends the sweep and reopens the laser (s). */
		double stallTimeout = 0.5;
		/** Pause between reconnection attempts (s). */
		double reconnectDelay = 0.5;
		/** Lines waiting longer than this for a head position are dropped
		 * (s). */
		double maxTiltWait = 1.0;
		/** JSON file with the capture counters, rewritten atomically every
		 * second and at the end; empty = none. */
		std::string statsFile;
	};

	/** Capture counters (also written to stats_file). */
	struct Stats
	{
		std::size_t lines = 0;  ///< observations emitted
		std::size_t crcErrors = 0;
		std::size_t faults = 0;  ///< stalls and disconnects detected
		std::size_t reconnects = 0;
		std::size_t sweepsComplete = 0, sweepsIncomplete = 0;
		std::size_t linesNoTilt = 0;     ///< no head position in time
		std::size_t linesDiscarded = 0;  ///< while the head was repositioned
		/** Scans whose range count is not FOV / resolution + 1. */
		std::size_t linesBadSize = 0;
		/** Lines without a tilt that fell between head positions more
		 * than 0.25 s apart (part of linesNoTilt). */
		std::size_t linesInGaps = 0;
		/** Head positions with a slow round trip (uncertain time) used
		 * because no precise one came for 0.12 s. */
		std::size_t slowHeadQueries = 0;
		double firstLineAge = 0;  ///< s from first to last emitted line
	};

	CTiltingLMS2xx();
	~CTiltingLMS2xx() override;

	/** Opens the head and the laser and starts the threads. Throws when the
	 * head cannot be opened or the configuration is inconsistent; a laser
	 * that is not there yet is retried in the background. */
	void initialize() override;
	void doProcess() override;

	/** Called by the rawlog-grabber plugin: a configuration or start-up
	 * error then also makes the process exit with status 1 when it ends
	 * (MRPT 2.5's rawlog-grabber logs a sensor thread's exception, stops
	 * and exits 0). Either way the error is first printed as one line,
	 * "CTiltingLMS2xx: [SECTION] what", before MRPT's report. */
	static void exitNonZeroOnStartupError();

	const TOptions& options() const { return m_options; }
	Stats stats() const;
	/** Measured lines per second since the first line. */
	double lineRate() const;
	/** The LMS2xx's own limit at the configured baud rate and resolution
	 * (lines/s). */
	double lineRateLimit() const;

protected:
	void loadConfig_sensorSpecific(
	    const mrpt::config::CConfigFileBase& configSource,
	    const std::string& section) override;

private:
	struct RawLine
	{
		mrpt::Clock::time_point t;
		mrpt::obs::CObservation2DRangeScan::Ptr scan;
	};
	/** initialize()'s work. */
	void start();
	void laserThread();
	void headThread();
	/** Head angle (PTU units) of tilt theta. */
	double headAngle(double theta) const;
	/** Sends the head to tilt theta; ignored while the PTU is gone. */
	void moveHead(double theta);
	/** The head's tilt now; false when it does not answer. */
	bool queryHead(double& theta);
	/** Closes and reopens the PTU, then sends it to `target`. */
	void reopenHead(double target);
	bool openLaser();
	void closeLaser();
	void writeStats() const;
	void stopThreads();

	TOptions m_options;
	std::shared_ptr<mrpt::hwdrivers::CSickLaserSerial> m_lms;
	std::shared_ptr<MonitoredSerialPort> m_lmsPort;
	std::unique_ptr<mrpt::hwdrivers::CPtuBase> m_ptu;
	std::atomic<bool> m_ptuOpen{false};
	/** 20 s of head positions; no interpolation over more than 0.25 s
	 * (about 6 polls: the head may have turned in between). */
	TiltHistory m_tilts{20.0, 0.25};

	std::thread m_laserThread, m_headThread;
	std::atomic<bool> m_stop{false};
	/** Set by the laser thread on a stall/disconnect, cleared by the head
	 * thread once it has handled it. */
	std::atomic<bool> m_laserFault{false};
	std::atomic<bool> m_laserOk{false};
	std::atomic<int64_t> m_lastLineTicks{0};

	mutable std::mutex m_mtx;  // guards m_pending and m_stats
	std::deque<RawLine> m_pending;
	Stats m_stats;
	std::size_t m_crcBase = 0;  // CRC errors of closed laser connections
	mrpt::Clock::time_point m_firstLine{}, m_lastLine{};
	mrpt::Clock::time_point m_lastStatsWrite{};
};

}  // namespace semnav
