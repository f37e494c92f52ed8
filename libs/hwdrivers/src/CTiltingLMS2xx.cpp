/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/core/bits_math.h>
#include <mrpt/hwdrivers/CPtuDPerception.h>
#include <mrpt/hwdrivers/CSickLaserSerial.h>
#include <mrpt/hwdrivers/CTuMicos.h>
#include <mrpt/system/datetime.h>
#include <semnav/common/AtomicFile.h>
#include <semnav/common/Error.h>
#include <semnav/common/OptionTable.h>
#include <semnav/hwdrivers/CTiltingLMS2xx.h>
#include <semnav/hwdrivers/Lms2xxTelegramParser.h>
#include <semnav/hwdrivers/MonitoredSerialPort.h>
#include <semnav/scan/TiltGeometry.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <mutex>
#include <nlohmann/json.hpp>

IMPLEMENTS_GENERIC_SENSOR(CTiltingLMS2xx, semnav)

namespace semnav
{
namespace
{
using Clock = mrpt::Clock;

/** b - a in seconds (any time points, unlike timeDifference()). */
inline double secondsBetween(
    mrpt::Clock::time_point a, mrpt::Clock::time_point b)
{
	return std::chrono::duration<double>(b - a).count();
}

Clock::duration seconds(double s)
{
	return std::chrono::duration_cast<Clock::duration>(
	    std::chrono::duration<double>(s));
}

/** MRPT's clock ticks (100 ns since 1601): nanoseconds since then overflow
 * int64 (UBSan). */
int64_t toTicks(Clock::time_point t)
{
	return t.time_since_epoch().count();
}

std::string where(const std::string& section, const std::string& key)
{
	return "[" + section + "] " + key;
}

/** What an exception says, in one line (MRPT's carry traces). */
std::string firstLine(const std::string& msg)
{
	// MRPT's exceptions: the line after "Message:" says what happened.
	if (const auto m = msg.find("Message:"); m != std::string::npos)
	{
		const auto b = msg.find_first_not_of(' ', m + 8);
		const auto e = msg.find('\n', b);
		return msg.substr(b, e == std::string::npos ? e : e - b);
	}
	std::size_t b = 0;
	while (b < msg.size())
	{
		const auto e = msg.find('\n', b);
		const std::string l =
		    msg.substr(b, e == std::string::npos ? std::string::npos : e - b);
		if (l.find_first_not_of(" \t\r") != std::string::npos) return l;
		if (e == std::string::npos) break;
		b = e + 1;
	}
	return msg;
}

std::atomic<bool> g_exitNonZeroOnStartupError{false};

/** At exit: the status becomes 1 (stdio flushed; later exit handlers and
 * static destructors are skipped: the grabber has closed its rawlog). */
void exitWithFailure()
{
	std::fflush(nullptr);
	std::_Exit(1);
}

/** One line naming the section, before MRPT's multi-line report. */
void reportStartupError(const std::string& section, const std::exception& e)
{
	std::string what = firstLine(e.what());
	if (what.rfind("[" + section + "]", 0) != 0)
		what = "[" + section + "] " + what;
	std::cerr << "CTiltingLMS2xx: " << what << std::endl;
	static std::once_flag once;
	if (g_exitNonZeroOnStartupError)
		std::call_once(once, [] { std::atexit(exitWithFailure); });
}

using O = CTiltingLMS2xx::TOptions;
const OptionTable<O>& optionTable()
{
	static const auto t =
	    OptionTable<O>()
	        .text("COM_port_LIN", &O::lmsPort, "Serial port of the LMS2xx.")
	        .integer(
	            "COM_baudRate", &O::baudRate, 9600, 500000,
	            "9600 | 38400 (RS-232) | 500000 (RS-422).")
	        .check(
	            [](const O& o) {
		            return o.baudRate == 9600 || o.baudRate == 38400 ||
		                   o.baudRate == 500000;
	            },
	            [](const O& o)
	            {
		            return "COM_baudRate = " + std::to_string(o.baudRate) +
		                   " is not an LMS2xx rate (9600, 38400, 500000)";
	            })
	        .integer(
	            "FOV", &O::fovDeg, 100, 180, "Field of view, deg: 100 | 180.")
	        .check(
	            [](const O& o) { return o.fovDeg == 100 || o.fovDeg == 180; },
	            "FOV must be 100 or 180")
	        .integer(
	            "resolution", &O::resolutionCdeg, 25, 100,
	            "Angular resolution, 1/100 deg: 25 | 50 | 100.")
	        .check(
	            [](const O& o)
	            {
		            return o.resolutionCdeg == 25 || o.resolutionCdeg == 50 ||
		                   o.resolutionCdeg == 100;
	            },
	            "resolution must be 25, 50 or 100")
	        .check(
	            [](const O& o)
	            { return o.resolutionCdeg != 25 || o.fovDeg == 100; },
	            "resolution = 25 needs FOV = 100 (LMS2xx)")
	        .flag("mm_mode", &O::mmMode, "Millimetre range mode.")
	        .text(
	            "ptu_type", &O::ptuType,
	            "dperception (Directed Perception PTU-46) | tumicos.")
	        .check(
	            [](const O& o) {
		            return o.ptuType == "dperception" || o.ptuType == "tumicos";
	            },
	            [](const O& o) {
		            return "ptu_type = '" + o.ptuType +
		                   "' (known: dperception, tumicos)";
	            })
	        .text("ptu_port", &O::ptuPort, "Serial port of the pan-tilt unit.")
	        .custom(
	            "ptu_axis",
	            [](O& o, const mrpt::config::CConfigFileBase& c,
	               const std::string& s)
	            {
		            const std::string axis =
		                c.read_string(s, "ptu_axis", std::string(1, o.ptuAxis));
		            if (axis != "T" && axis != "P")
			            throw ConfigError(
			                "[" + s + "] ptu_axis must be T or P");
		            o.ptuAxis = axis[0];
	            },
	            [](const O& o) { return std::string(1, o.ptuAxis); },
	            "Axis that tilts the laser: T | P.")
	        .real(
	            "ptu_sign", &O::ptuSign, -1, 1,
	            "theta = ptu_sign * head tilt + ptu_offset_deg (theta > 0 "
	            "looks up).")
	        .check(
	            [](const O& o) { return o.ptuSign == 1 || o.ptuSign == -1; },
	            "ptu_sign must be 1 or -1")
	        .angle("ptu_offset_deg", &O::ptuOffset, -180, 180, "See ptu_sign.")
	        .angle(
	            "theta_min_deg", &O::thetaMin, -90, 90,
	            "Lowest tilt of a sweep.")
	        .angle(
	            "theta_max_deg", &O::thetaMax, -90, 90,
	            "Highest tilt of a sweep.")
	        .check(
	            [](const O& o) { return o.thetaMax > o.thetaMin; },
	            "theta_max_deg must be larger than theta_min_deg")
	        .angle(
	            "tilt_speed_deg_s", &O::tiltSpeed, 0.01, 300,
	            "Tilt speed (0.5 deg per line at the lines/s of the baud "
	            "rate).")
	        .real(
	            "ptu_poll_period_s", &O::ptuPollPeriod, 0.001, 1.0,
	            "The tilt is polled this often.")
	        .realAt(
	            "mount_x_m", [](O& o) -> double& { return o.mount.x; }, -10, 10,
	            "Tilt axis in the robot frame: x.")
	        .realAt(
	            "mount_y_m", [](O& o) -> double& { return o.mount.y; }, -10, 10,
	            "Tilt axis in the robot frame: y.")
	        .realAt(
	            "mount_z_m", [](O& o) -> double& { return o.mount.z; }, -10, 10,
	            "Tilt axis in the robot frame: z.")
	        .real(
	            "max_range_m", &O::maxRange, 0.1, 81.0,
	            "Farther returns are no returns.")
	        .real(
	            "range_noise_m", &O::rangeNoise, 0, 1,
	            "Range noise (std dev) written into the observations.")
	        .real(
	            "stall_timeout_s", &O::stallTimeout, 0.05, 60,
	            "No data for this long: the port is reopened.")
	        .real(
	            "reconnect_delay_s", &O::reconnectDelay, 0.01, 60,
	            "Wait between reconnection attempts.")
	        .real(
	            "max_tilt_wait_s", &O::maxTiltWait, 0.05, 60,
	            "Longest wait for a tilt reading.")
	        .text(
	            "stats_file", &O::statsFile,
	            "Capture statistics (JSON) written here; empty: none.");
	return t;
}

/** rawlog-grabber's keys of a sensor section. */
const std::vector<std::string> kGrabberKeys{
    "driver",          "process_rate", "max_queue_len",
    "grab_decimation", "sensorLabel",  "rawlog-grabber-ignore"};

/** Sleeps up to `s` seconds, waking early when `stop` is set. */
void sleepUnless(const std::atomic<bool>& stop, double s)
{
	const auto end = Clock::now() + seconds(s);
	while (!stop && Clock::now() < end)
		std::this_thread::sleep_for(std::chrono::milliseconds(10));
}
}  // namespace

void CTiltingLMS2xx::TOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& c, const std::string& s)
{
	optionTable().load(*this, c, s, kGrabberKeys);
}

void CTiltingLMS2xx::TOptions::saveToConfigFile(
    mrpt::config::CConfigFileBase& c, const std::string& s) const
{
	optionTable().save(*this, c, s);
}

CTiltingLMS2xx::CTiltingLMS2xx() : mrpt::system::COutputLogger("CTiltingLMS2xx")
{
	m_sensorLabel = "TILT_LMS";
}

CTiltingLMS2xx::~CTiltingLMS2xx()
{
	// MRPT's drivers throw on closed ports; nothing may leave a destructor.
	try
	{
		stopThreads();
		closeLaser();
		if (m_ptu && m_ptuOpen)
		{
			m_ptu->halt(m_options.ptuAxis);
			m_ptu->close();
		}
		writeStats();
	}
	catch (const std::exception& e)
	{
		MRPT_LOG_ERROR_FMT("closing: %s", firstLine(e.what()).c_str());
	}
	catch (...)
	{
	}
}

void CTiltingLMS2xx::exitNonZeroOnStartupError()
{
	g_exitNonZeroOnStartupError = true;
}

void CTiltingLMS2xx::loadConfig_sensorSpecific(
    const mrpt::config::CConfigFileBase& c, const std::string& section)
{
	try
	{
		TOptions o;
		o.loadFromConfigFile(c, section);
		if (o.lmsPort.empty())
			throw ConfigError(where(section, "COM_port_LIN") + " is missing");
		if (o.ptuPort.empty())
			throw ConfigError(where(section, "ptu_port") + " is missing");
		m_options = o;
	}
	catch (const std::exception& e)
	{
		reportStartupError(section, e);
		throw;
	}
}

double CTiltingLMS2xx::lineRateLimit() const
{
	const std::size_t beams =
	    static_cast<std::size_t>(
	        std::lround(m_options.fovDeg * 100.0 / m_options.resolutionCdeg)) +
	    1;
	// 75 Hz mirror; 0.5 deg takes 2 interlaced turns, 0.25 deg 4.
	const double scanHz = 75.0 * m_options.resolutionCdeg / 100.0;
	return lms2xx::lineRateLimit(m_options.baudRate, beams, scanHz);
}

void CTiltingLMS2xx::initialize()
{
	try
	{
		start();
	}
	catch (const std::exception& e)
	{
		reportStartupError(m_sensorLabel, e);
		throw;
	}
}

void CTiltingLMS2xx::start()
{
	if (m_options.ptuType == "tumicos")
		m_ptu = std::make_unique<mrpt::hwdrivers::CTuMicos>();
	else
		m_ptu = std::make_unique<mrpt::hwdrivers::CPtuDPerception>();
	m_ptuOpen = m_ptu->init(m_options.ptuPort);
	if (!m_ptuOpen)
		throw Error(
		    "CTiltingLMS2xx: cannot open the pan-tilt unit (" +
		    m_options.ptuType + ") at " + m_options.ptuPort);
	if (!m_ptu->speed(m_options.ptuAxis, m_options.tiltSpeed))
		MRPT_LOG_WARN("the head refused the tilt speed; using its own");
	m_state = ssWorking;
	MRPT_LOG_INFO_FMT(
	    "head on %s, laser on %s at %d baud (limit %.2f lines/s)",
	    m_options.ptuPort.c_str(), m_options.lmsPort.c_str(),
	    m_options.baudRate, lineRateLimit());
	m_stop = false;
	m_headThread = std::thread([this] { headThread(); });
	m_laserThread = std::thread([this] { laserThread(); });
}

void CTiltingLMS2xx::stopThreads()
{
	m_stop = true;
	if (m_laserThread.joinable()) m_laserThread.join();
	if (m_headThread.joinable()) m_headThread.join();
}

namespace
{
/** Sends an LMS2xx command and waits up to `timeout` s for a good response
 * telegram whose command byte is `reply` (stale bytes are skipped). */
bool lmsCommand(
    mrpt::comms::CSerialPort& port, const std::vector<uint8_t>& payload,
    uint8_t reply, double timeout)
{
	port.purgeBuffers();
	const auto t = lms2xx::buildTelegram(lms2xx::kHostAddress, payload);
	port.Write(t.data(), t.size());
	lms2xx::TelegramParser parser(lms2xx::kLmsAddress);
	const auto end = Clock::now() + seconds(timeout);
	uint8_t buf[512];
	while (Clock::now() < end && port.isOpen())
	{
		const size_t n = port.Read(buf, sizeof(buf));
		parser.feed(buf, n);
		while (auto r = parser.next())
			if (r->crcOk && r->command() == reply) return true;
	}
	return false;
}

/** Gets the laser ready for MRPT's driver: stops its continuous output and
 * brings it to `desiredBaud`, with timeouts that tolerate a busy host.
 * MRPT 2.5's CSickLaserSerial expects an ACK within 65 ms and resends
 * otherwise, reads a response of any declared length into a 2000-byte
 * buffer (a device still streaming can overrun it) and spends about 5 s
 * before it tells that no device answers. After this, its own detection
 * finds the device at the desired rate at once. False when nothing
 * answers at any rate. */
bool prepareLaser(const std::string& path, int desiredBaud)
{
	mrpt::comms::CSerialPort port;
	try
	{
		port.setSerialPortName(path);
		port.open();
		port.setTimeouts(10, 0, 10, 0, 50);
		const std::vector<uint8_t> stop{0x20, 0x25};
		for (int baud : {desiredBaud, 9600, 38400, 500000})
		{
			port.setConfig(baud);
			bool answered = false;
			for (int attempt = 0; attempt < 2 && !answered; attempt++)
				answered = lmsCommand(port, stop, 0xA0, 0.3);
			if (!answered) continue;
			if (baud == desiredBaud) return true;
			const uint8_t code = desiredBaud == 500000  ? 0x48
			                     : desiredBaud == 38400 ? 0x40
			                                            : 0x42;
			if (!lmsCommand(port, {0x20, code}, 0xA0, 1.0)) return false;
			port.setConfig(desiredBaud);
			std::this_thread::sleep_for(std::chrono::milliseconds(100));
			return lmsCommand(port, stop, 0xA0, 0.5);
		}
	}
	catch (const std::exception&)
	{
	}
	return false;
}
}  // namespace

bool CTiltingLMS2xx::openLaser()
{
	if (!prepareLaser(m_options.lmsPort, m_options.baudRate))
	{
		MRPT_LOG_THROTTLE_WARN_FMT(
		    5.0, "no answer from the laser at %s (retrying)",
		    m_options.lmsPort.c_str());
		return false;
	}
	auto port = std::make_shared<MonitoredSerialPort>();
	auto lms = std::make_shared<mrpt::hwdrivers::CSickLaserSerial>();
	lms->setSerialPort(m_options.lmsPort);
	lms->setBaudRate(m_options.baudRate);
	lms->setMillimeterMode(m_options.mmMode);
	lms->setScanFOV(m_options.fovDeg);
	lms->setScanResolution(m_options.resolutionCdeg);
	lms->bindIO(port);
	try
	{
		lms->initialize();
	}
	catch (const std::exception& e)
	{
		MRPT_LOG_WARN_FMT(
		    "laser at %s not ready: %s", m_options.lmsPort.c_str(),
		    firstLine(e.what()).c_str());
		return false;
	}
	std::lock_guard<std::mutex> lk(m_mtx);
	m_lms = lms;
	m_lmsPort = port;
	return true;
}

void CTiltingLMS2xx::closeLaser()
{
	std::shared_ptr<MonitoredSerialPort> port;
	{
		std::lock_guard<std::mutex> lk(m_mtx);
		if (m_lmsPort) m_crcBase += m_lmsPort->crcErrors();
		port = m_lmsPort;
		m_lmsPort.reset();
	}
	// The MRPT driver stops the continuous output when destroyed.
	m_lms.reset();
	if (port && port->isOpen()) port->close();
}

void CTiltingLMS2xx::laserThread()
{
	const std::size_t beams =
	    static_cast<std::size_t>(
	        std::lround(m_options.fovDeg * 100.0 / m_options.resolutionCdeg)) +
	    1;
	const double txTime = lms2xx::transmissionTime(
	    lms2xx::measuredValuesBytes(
	        static_cast<std::size_t>(std::lround(
	            m_options.fovDeg * 100.0 / m_options.resolutionCdeg)) +
	        1),
	    m_options.baudRate);
	bool everOpen = false;
	Clock::time_point lastGood = Clock::now();
	// 75 Hz mirror; 0.5 deg interlaces 2 turns, 0.25 deg 4.

	while (!m_stop)
	{
		if (!m_lms)
		{
			if (!openLaser())
			{
				sleepUnless(m_stop, m_options.reconnectDelay);
				continue;
			}
			if (everOpen)
			{
				std::lock_guard<std::mutex> lk(m_mtx);
				m_stats.reconnects++;
				MRPT_LOG_INFO("laser reconnected");
			}
			everOpen = true;
			lastGood = Clock::now();
		}
		bool has = false, hwError = false;
		mrpt::obs::CObservation2DRangeScan obs;
		// CSerialPort closes itself when the device goes away (EIO); then
		// MRPT's driver would retry opening at once, in a busy loop.
		const bool unplugged = !m_lmsPort->isOpen();
		if (!unplugged) m_lms->doProcessSimple(has, obs, hwError);
		const auto now = Clock::now();
		if (!has)
		{
			if (unplugged ||
			    secondsBetween(lastGood, now) > m_options.stallTimeout)
			{
				MRPT_LOG_WARN_FMT(
				    "%s after %.2f s without a scan: sweep ended incomplete, "
				    "reconnecting",
				    unplugged ? "laser disconnected" : "laser stalled",
				    secondsBetween(lastGood, now));
				{
					std::lock_guard<std::mutex> lk(m_mtx);
					m_stats.faults++;
				}
				m_laserOk = false;
				m_laserFault = true;
				closeLaser();
			}
			continue;
		}
		lastGood = now;
		const std::size_t n = obs.getScanSize();
		if (n != beams)
		{
			// Not the field of view and resolution set up: its bearings
			// are unknown, so the line cannot be used.
			MRPT_LOG_THROTTLE_WARN_FMT(
			    5.0, "scan of %u ranges instead of %u dropped",
			    static_cast<unsigned>(n), static_cast<unsigned>(beams));
			std::lock_guard<std::mutex> lk(m_mtx);
			m_stats.linesBadSize++;
			continue;
		}
		auto scan = mrpt::obs::CObservation2DRangeScan::Create();
		scan->sensorLabel = m_sensorLabel;
		scan->timestamp = obs.timestamp - seconds(txTime);
		// The n beams span the field of view, whatever resolution the
		// device was left at.
		scan->aperture = static_cast<float>(mrpt::DEG2RAD(m_options.fovDeg));
		scan->rightToLeft = true;
		scan->maxRange = static_cast<float>(m_options.maxRange);
		scan->stdError = static_cast<float>(m_options.rangeNoise);
		scan->resizeScan(n);
		for (std::size_t i = 0; i < n; i++)
		{
			const float r = obs.getScanRange(i);
			// LMS2xx no-return codes (8183..8191 mm) lie beyond max range.
			const bool ok = r > 0 && r <= m_options.maxRange;
			scan->setScanRange(i, ok ? r : scan->maxRange);
			scan->setScanRangeValidity(i, ok);
		}
		m_laserOk = true;
		m_lastLineTicks = toTicks(scan->timestamp);
		std::lock_guard<std::mutex> lk(m_mtx);
		m_pending.push_back({scan->timestamp, scan});
	}
}

double CTiltingLMS2xx::headAngle(double theta) const
{
	return (theta - m_options.ptuOffset) * m_options.ptuSign;
}

// MRPT's PTU drivers throw once the port has gone (unplugged): count that as
// no answer.
void CTiltingLMS2xx::moveHead(double theta)
{
	try
	{
		if (m_ptuOpen) m_ptu->moveToAbsPos(m_options.ptuAxis, headAngle(theta));
	}
	catch (const std::exception&)
	{
	}
}

bool CTiltingLMS2xx::queryHead(double& theta)
{
	double angle = 0;
	try
	{
		if (!m_ptuOpen || !m_ptu->absPosQ(m_options.ptuAxis, angle))
			return false;
	}
	catch (const std::exception&)
	{
		return false;
	}
	theta = m_options.ptuSign * angle + m_options.ptuOffset;
	return true;
}

void CTiltingLMS2xx::reopenHead(double target)
{
	MRPT_LOG_ERROR("the head does not answer: reopening it");
	m_ptu->close();
	m_ptuOpen = m_ptu->init(m_options.ptuPort);
	if (!m_ptuOpen) return;
	try
	{
		m_ptu->speed(m_options.ptuAxis, m_options.tiltSpeed);
	}
	catch (const std::exception&)
	{
	}
	moveHead(target);
}

void CTiltingLMS2xx::headThread()
{
	const auto& o = m_options;
	const double res =
	    o.ptuAxis == 'T' ? m_ptu->tiltResolution : m_ptu->panResolution;
	const double tol = std::max(1.5 * std::abs(res), mrpt::DEG2RAD(0.05));
	// Start: go (unrecorded) to thetaMin, then sweep up.
	bool sweeping = false;
	int dir = 1;
	double target = o.thetaMin;
	moveHead(target);
	int failures = 0;
	auto faultTime = Clock::now();
	// "TP " at the PTU's 9600 baud.
	const double queryTx = lms2xx::transmissionTime(3, 9600);
	constexpr double kSpanMargin = 0.006;
	double minSpan = 1e9;
	while (!m_stop)
	{
		const auto t0 = Clock::now();
		double theta = 0;
		if (!queryHead(theta))
		{
			if (++failures >= 10)
			{
				reopenHead(target);
				failures = 0;
			}
			sleepUnless(m_stop, o.ptuPollPeriod);
			continue;
		}
		failures = 0;
		const auto t1 = Clock::now();
		// The head reports its position when it gets the query, about
		// t0 + the query's line time; that holds when the round trip was as
		// short as the shortest seen (no thread was held up on either
		// side). Slower round trips are kept out of the tilt history.
		const double span = secondsBetween(t0, t1);
		minSpan = std::min(minSpan + 1e-4, span);
		const bool wasSweeping = sweeping;
		bool turned = false;

		if (m_laserFault.exchange(false))
		{
			if (sweeping)
			{
				std::lock_guard<std::mutex> lk(m_mtx);
				m_stats.sweepsIncomplete++;
			}
			// Back to where the interrupted sweep started, not recording.
			sweeping = false;
			target = dir > 0 ? o.thetaMin : o.thetaMax;
			moveHead(target);
			faultTime = t0;
		}
		else if (!sweeping)
		{
			const bool lineSinceFault =
			    m_laserOk && m_lastLineTicks > toTicks(faultTime);
			if (std::abs(theta - target) <= tol && lineSinceFault)
			{
				sweeping = true;
				target = dir > 0 ? o.thetaMax : o.thetaMin;
				moveHead(target);
			}
		}
		else if (std::abs(theta - target) <= tol)
		{
			{
				std::lock_guard<std::mutex> lk(m_mtx);
				m_stats.sweepsComplete++;
			}
			turned = true;
			dir = -dir;
			target = dir > 0 ? o.thetaMax : o.thetaMin;
			moveHead(target);
		}
		// A sweep starts or turns at this sample (the head waits at the
		// end, so its time matters little); an interrupted one ends here.
		if (span <= minSpan + kSpanMargin || sweeping != wasSweeping || turned)
			m_tilts.add(
			    {t0 + seconds(queryTx), theta, sweeping || wasSweeping});
		else
		{
			std::lock_guard<std::mutex> lk(m_mtx);
			m_stats.slowHeadQueries++;
		}
		const double spent = secondsBetween(t0, Clock::now());
		sleepUnless(m_stop, std::max(0.0, o.ptuPollPeriod - spent));
	}
}

void CTiltingLMS2xx::doProcess()
{
	std::vector<mrpt::serialization::CSerializable::Ptr> out;
	{
		std::lock_guard<std::mutex> lk(m_mtx);
		const auto now = Clock::now();
		while (!m_pending.empty())
		{
			RawLine& l = m_pending.front();
			double theta = 0;
			const auto r = m_tilts.tiltAt(l.t, theta);
			if (r == TiltHistory::Lookup::NotYet &&
			    secondsBetween(l.t, now) <= m_options.maxTiltWait)
				break;
			if (r == TiltHistory::Lookup::Ok)
			{
				l.scan->sensorPose = tiltedSensorPose(m_options.mount, theta);
				out.push_back(l.scan);
				if (m_stats.lines == 0) m_firstLine = l.t;
				m_lastLine = l.t;
				m_stats.lines++;
			}
			else if (r == TiltHistory::Lookup::NotRecording)
				m_stats.linesDiscarded++;
			else
			{
				m_stats.linesNoTilt++;
				if (r == TiltHistory::Lookup::Gap) m_stats.linesInGaps++;
			}
			m_pending.pop_front();
		}
	}
	for (auto& o : out) appendObservation(o);
	const auto now = Clock::now();
	if (secondsBetween(m_lastStatsWrite, now) >= 1.0)
	{
		m_lastStatsWrite = now;
		writeStats();
	}
}

CTiltingLMS2xx::Stats CTiltingLMS2xx::stats() const
{
	std::lock_guard<std::mutex> lk(m_mtx);
	Stats s = m_stats;
	s.crcErrors = m_crcBase + (m_lmsPort ? m_lmsPort->crcErrors() : 0);
	s.firstLineAge = s.lines > 1 ? secondsBetween(m_firstLine, m_lastLine) : 0;
	return s;
}

double CTiltingLMS2xx::lineRate() const
{
	const Stats s = stats();
	return s.firstLineAge > 0 ? (s.lines - 1) / s.firstLineAge : 0;
}

void CTiltingLMS2xx::writeStats() const
{
	if (m_options.statsFile.empty()) return;
	const Stats s = stats();
	nlohmann::json j;
	j["lines"] = s.lines;
	j["crc_errors"] = s.crcErrors;
	j["faults"] = s.faults;
	j["reconnects"] = s.reconnects;
	j["sweeps_complete"] = s.sweepsComplete;
	j["sweeps_incomplete"] = s.sweepsIncomplete;
	j["lines_no_tilt"] = s.linesNoTilt;
	j["lines_in_gaps"] = s.linesInGaps;
	j["lines_bad_size"] = s.linesBadSize;
	j["lines_discarded"] = s.linesDiscarded;
	j["slow_head_queries"] = s.slowHeadQueries;
	j["lines_per_s"] = lineRate();
	j["lines_per_s_limit"] = lineRateLimit();
	j["baud"] = m_options.baudRate;
	writeFileAtomically(m_options.statsFile, j.dump() + "\n");
}

}  // namespace semnav
