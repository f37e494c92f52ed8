/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/hwdrivers/MonitoredSerialPort.h>

namespace semnav
{
namespace
{
/** MRPT's CSickLaserSerial::m_received_frame_buffer size. */
constexpr std::size_t kMrptFrameBuffer = 2000;
}  // namespace

MonitoredSerialPort::MonitoredSerialPort() : m_parser(lms2xx::kLmsAddress) {}

size_t MonitoredSerialPort::Write(const void* Buffer, size_t Count)
{
	{
		std::lock_guard<std::mutex> lk(m_mtx);
		m_guard = Guard::Ack;
		m_frameBytes = 0;
		m_guardSince = std::chrono::steady_clock::now();
	}
	return mrpt::comms::CSerialPort::Write(Buffer, Count);
}

void MonitoredSerialPort::followByte(uint8_t b)
{
	// Mirrors LMS_waitACK() and LMS_waitIncomingFrame() of MRPT 2.5.
	if (m_guard == Guard::Ack)
	{
		if (b == lms2xx::kAck)
		{
			m_guard = Guard::Frame;
			m_frameBytes = 0;
		}
		return;
	}
	if (m_guard != Guard::Frame) return;
	if (m_frameBytes == 0)
	{
		if (b == lms2xx::kStx) m_frameBytes = 1;
		return;
	}
	if (m_frameBytes == 1)
	{
		if (b == lms2xx::kLmsAddress) m_frameBytes = 2;
		return;  // MRPT skips other bytes here
	}
	if (m_frameBytes < 4) m_len[m_frameBytes - 2] = b;
	m_frameBytes++;
	if (m_frameBytes == 4)
	{
		const std::size_t len = m_len[0] | (m_len[1] << 8);
		if (len + 6 > kMrptFrameBuffer)
		{
			m_guard = Guard::Blocked;
			m_blocked++;
		}
		return;
	}
	const std::size_t len = m_len[0] | (m_len[1] << 8);
	if (m_frameBytes >= len + 6) m_guard = Guard::Idle;
}

size_t MonitoredSerialPort::Read(void* Buffer, size_t Count)
{
	{
		std::lock_guard<std::mutex> lk(m_mtx);
		// The driver gives up on a response after at most 600 ms.
		if (m_guard == Guard::Blocked &&
		    std::chrono::steady_clock::now() - m_guardSince >
		        std::chrono::seconds(2))
			m_guard = Guard::Idle;
		if (m_guard == Guard::Blocked) return 0;
		// A multi-byte read is the continuous-scan reader, not a response.
		if (Count > 1 && m_guard != Guard::Idle) m_guard = Guard::Idle;
	}
	const size_t n = mrpt::comms::CSerialPort::Read(Buffer, Count);
	if (n == 0) return n;
	std::lock_guard<std::mutex> lk(m_mtx);
	const auto* bytes = static_cast<const uint8_t*>(Buffer);
	if (Count == 1) followByte(bytes[0]);
	m_parser.feed(bytes, n);
	while (auto t = m_parser.next())
	{
		if (!t->crcOk)
			m_crcErrors++;
		else if (t->command() == lms2xx::kCmdMeasuredValues)
			m_goodScans++;
	}
	return n;
}

std::size_t MonitoredSerialPort::skippedBytes() const
{
	std::lock_guard<std::mutex> lk(m_mtx);
	return m_parser.skippedBytes();
}

}  // namespace semnav
