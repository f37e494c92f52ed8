/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/core/bits_math.h>
#include <semnav/common/Error.h>
#include <semnav/emulation/LmsEmulator.h>
#include <semnav/emulation/SceneLineCaster.h>
#include <semnav/hwdrivers/Lms2xxTelegramParser.h>
#include <semnav/hwdrivers/TiltHeadModel.h>
#include <semnav/scan/TiltGeometry.h>

#include <chrono>
#include <cmath>
#include <optional>

namespace semnav
{
namespace
{
using SClock = std::chrono::steady_clock;
double secondsSince(SClock::time_point t0)
{
	return std::chrono::duration<double>(SClock::now() - t0).count();
}
}  // namespace

LmsEmulator::LmsEmulator(
    const SceneLineCaster& caster, const TiltHeadModel& head,
    const Options& options)
    : mrpt::system::COutputLogger("LmsEmulator"),
      m_caster(caster),
      m_head(head),
      m_opt(options),
      m_pty(options.linkPath),
      m_rng(options.seed)
{
	powerOn();
}

LmsEmulator::~LmsEmulator()
{
	stop();
}

void LmsEmulator::powerOn()
{
	m_baud = m_opt.powerOnBaud;
	m_pendingBaud = 0;
	m_mm = false;
	m_continuous = false;
	m_fov = 180;
	m_res = 100;
}

void LmsEmulator::start()
{
	if (!m_opt.truthLog.empty())
	{
		m_truth.open(m_opt.truthLog);
		if (!m_truth) throw IoError("cannot write " + m_opt.truthLog);
		m_truth.precision(17);
	}
	m_pty.open();
	m_stop = false;
	m_thread = std::thread([this] { run(); });
}

void LmsEmulator::stop()
{
	m_stop = true;
	if (m_thread.joinable()) m_thread.join();
	m_pty.close();
}

LmsEmulator::Counters LmsEmulator::counters() const
{
	std::lock_guard<std::mutex> lk(m_cmtx);
	return m_counters;
}

void LmsEmulator::respond(const std::vector<uint8_t>& payload)
{
	const auto t = lms2xx::buildTelegram(lms2xx::kLmsAddress, payload);
	m_pty.write(t.data(), t.size(), m_baud);
}

void LmsEmulator::handle(const std::vector<uint8_t>& p)
{
	{
		std::lock_guard<std::mutex> lk(m_cmtx);
		m_counters.commands++;
	}
	const uint8_t ack = lms2xx::kAck;
	m_pty.write(&ack, 1, m_baud);
	const uint8_t status = 0x10;
	switch (p[0])
	{
		case 0x20:  // operating mode
		{
			const uint8_t mode = p.size() > 1 ? p[1] : 0xFF;
			bool ok = true;
			switch (mode)
			{
				case 0x00:  // installation mode, password SICK_LMS
					ok = p.size() == 10 &&
					     std::string(p.begin() + 2, p.end()) == "SICK_LMS";
					break;
				case 0x24:
					m_continuous = true;
					break;
				case 0x25:
					m_continuous = false;
					break;
				case 0x40:
					m_pendingBaud = 38400;
					break;
				case 0x41:
					m_pendingBaud = 19200;
					break;
				case 0x42:
					m_pendingBaud = 9600;
					break;
				case 0x48:
					m_pendingBaud = 500000;
					break;
				default:
					ok = false;
			}
			respond({0xA0, static_cast<uint8_t>(ok ? 0x00 : 0x01), status});
			if (m_pendingBaud)
			{
				m_baud = m_pendingBaud;
				m_pendingBaud = 0;
			}
			break;
		}
		case 0x31:  // status: version string, then zeros
		{
			std::vector<uint8_t> r{0xB1};
			const std::string version = "LMS200;30106  EMU";
			r.insert(r.end(), version.begin(), version.end());
			r.resize(152, 0x00);
			r.push_back(status);
			respond(r);
			break;
		}
		case 0x74:  // read configuration (35-byte payload, as MRPT expects)
		{
			std::vector<uint8_t> r(35, 0x00);
			r[0] = 0xF4;
			r[1] = 0x00;
			r[2] = 0x46;                // blanking, etc.: arbitrary but fixed
			r[6] = m_mm ? 0x06 : 0x00;  // measuring mode
			r[7] = m_mm ? 0x01 : 0x00;  // unit: 1 = mm
			r[34] = status;
			respond(r);
			break;
		}
		case 0x77:  // write configuration
		{
			if (p.size() >= 8) m_mm = p[7] == 0x01;
			std::vector<uint8_t> r(p.begin(), p.end());
			r[0] = 0xF7;
			r.insert(r.begin() + 1, 0x01);  // accepted
			r.resize(35);
			r[34] = status;
			respond(r);
			break;
		}
		case 0x3B:  // angle range and resolution
		{
			if (p.size() < 5)
			{
				respond({0xBB, 0x00, 0, 0, 0, 0, status});
				break;
			}
			const int fov = p[1] | (p[2] << 8);
			const int res = p[3] | (p[4] << 8);
			const bool ok = (fov == 100 || fov == 180) &&
			                (res == 25 || res == 50 || res == 100) &&
			                !(res == 25 && fov != 100);
			if (ok)
			{
				m_fov = fov;
				m_res = res;
			}
			respond(
			    {0xBB, static_cast<uint8_t>(ok ? 1 : 0), p[1], p[2], p[3], p[4],
			     status});
			break;
		}
		default:
			respond({0x92, status});  // "not acknowledged" answer
	}
}

void LmsEmulator::sendScan()
{
	const auto now = SClock::now();
	const double theta = m_head.angle(now);
	if (m_truth.is_open())
		m_truth << std::chrono::duration<double>(
		               std::chrono::system_clock::now().time_since_epoch())
		               .count()
		        << ' ' << theta << '\n';
	const std::size_t n =
	    static_cast<std::size_t>(std::lround(m_fov * 100.0 / m_res)) + 1;
	std::vector<double> bearings(n);
	for (std::size_t i = 0; i < n; i++)
		bearings[i] = mrpt::DEG2RAD(-0.5 * m_fov + i * m_res / 100.0);
	const auto truth = m_caster.cast(
	    m_opt.poseSource ? m_opt.poseSource() : m_opt.robotPose,
	    tiltedSensorPose(m_caster.spec().mount, theta), bearings,
	    m_opt.maxRange);
	std::normal_distribution<double> nd(0.0, 1.0);
	const double unit = m_mm ? 0.001 : 0.01;
	std::vector<uint16_t> codes(n);
	for (std::size_t i = 0; i < n; i++)
	{
		const double meas = truth[i] + m_opt.rangeNoise * nd(m_rng);
		const bool ok = truth[i] > 0 && meas > 0 && meas <= m_opt.maxRange;
		codes[i] = ok ? static_cast<uint16_t>(std::lround(meas / unit))
		              : static_cast<uint16_t>(0x1FFF);
	}
	auto t = lms2xx::buildMeasuredValues(codes, m_mm);
	std::uniform_real_distribution<double> u(0.0, 1.0);
	if (u(m_rng) < m_opt.crcErrorRate)
	{
		t[7 + 2 * (n / 2)] ^= 0x01;  // one bit of a range
		std::lock_guard<std::mutex> lk(m_cmtx);
		m_counters.crcInjected++;
	}
	if (u(m_rng) < m_opt.dropByteRate)
	{
		t.erase(t.begin() + 7 + n);
		std::lock_guard<std::mutex> lk(m_cmtx);
		m_counters.bytesDropped++;
	}
	m_pty.write(t.data(), t.size(), m_baud);
	std::lock_guard<std::mutex> lk(m_cmtx);
	m_counters.scansSent++;
}

void LmsEmulator::run()
{
	const auto t0 = SClock::now();
	lms2xx::TelegramParser parser(lms2xx::kHostAddress);
	bool stallCounted = false, disconnected = false;
	auto nextScan = SClock::now();
	uint8_t buf[1024];
	// Fault times count from the first continuous output, so they fall
	// mid-capture however long the client's setup took.
	std::optional<SClock::time_point> streamStart;
	while (!m_stop)
	{
		if (m_continuous && !streamStart) streamStart = SClock::now();
		const double t = streamStart ? secondsSince(*streamStart) : -1.0;
		if (!disconnected && m_opt.disconnectAt >= 0 && t >= 0 &&
		    t >= m_opt.disconnectAt)
		{
			disconnected = true;
			MRPT_LOG_WARN("fault: disconnect");
			m_pty.close();
			{
				std::lock_guard<std::mutex> lk(m_cmtx);
				m_counters.disconnects++;
			}
			const auto until =
			    SClock::now() +
			    std::chrono::duration_cast<SClock::duration>(
			        std::chrono::duration<double>(m_opt.disconnectFor));
			while (!m_stop && SClock::now() < until)
				std::this_thread::sleep_for(std::chrono::milliseconds(10));
			if (m_stop) break;
			powerOn();
			parser.reset();
			m_pty.open();
			MRPT_LOG_WARN_FMT(
			    "fault: reconnected as %s", m_pty.slavePath().c_str());
			continue;
		}
		const bool stalled = m_opt.stallAt >= 0 && t >= 0 &&
		                     t >= m_opt.stallAt &&
		                     t < m_opt.stallAt + m_opt.stallFor;
		if (stalled && !stallCounted)
		{
			stallCounted = true;
			MRPT_LOG_WARN("fault: stall");
			std::lock_guard<std::mutex> lk(m_cmtx);
			m_counters.stalls++;
		}
		// Wait for input until the next scan is due.
		// 75 Hz mirror; finer resolutions interlace 2 or 4 turns.
		const double scanPeriod = (100.0 / m_res) / 75.0;
		int waitMs = 5;
		if (m_continuous)
			waitMs = std::max(
			    0, static_cast<int>(std::chrono::duration<double, std::milli>(
			                            nextScan - SClock::now())
			                            .count()));
		const std::size_t n =
		    m_pty.read(buf, sizeof(buf), std::min(waitMs, 20));
		// Bytes sent at another baud rate are noise to the device.
		if (n > 0 && !stalled && m_pty.clientBaud() == m_baud)
		{
			parser.feed(buf, n);
			while (auto tg = parser.next())
			{
				if (!tg->crcOk || tg->payloadSize() == 0)
				{
					const uint8_t nack = lms2xx::kNack;
					m_pty.write(&nack, 1, m_baud);
					std::lock_guard<std::mutex> lk(m_cmtx);
					m_counters.nacks++;
					continue;
				}
				handle(std::vector<uint8_t>(
				    tg->payload(), tg->payload() + tg->payloadSize()));
			}
		}
		if (m_continuous && !stalled && SClock::now() >= nextScan)
		{
			if (m_pty.clientBaud() == m_baud) sendScan();
			// Next scan of the mirror's grid after the line is free.
			const double since = secondsSince(t0);
			nextScan =
			    t0 +
			    std::chrono::duration_cast<SClock::duration>(
			        std::chrono::duration<double>(
			            (std::floor(since / scanPeriod) + 1) * scanPeriod));
		}
	}
}

}  // namespace semnav
