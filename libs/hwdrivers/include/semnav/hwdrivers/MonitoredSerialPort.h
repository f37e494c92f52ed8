/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/comms/CSerialPort.h>
#include <semnav/hwdrivers/Lms2xxTelegramParser.h>

#include <atomic>
#include <chrono>
#include <cstddef>
#include <mutex>

namespace semnav
{
/** A CSerialPort that watches the LMS2xx telegrams read through it.
 *
 * Bound to MRPT's CSickLaserSerial with bindIO(), it sees every byte the
 * driver reads and parses them like the driver does, so it can count what
 * the driver drops silently: telegrams with a bad CRC and skipped bytes.
 *
 * It also guards MRPT 2.5's LMS_waitIncomingFrame(), which stores a
 * response of whatever length its header declares into a 2000-byte buffer:
 * after a command is written it follows the driver's framing (ACK, then
 * STX ... 0x80, length) and, when a header announces more than the buffer
 * holds (a false start inside streamed scan data), reads nothing more
 * until the next command, so the driver times out instead of overrunning
 * its buffer. */
class MonitoredSerialPort : public mrpt::comms::CSerialPort
{
public:
	MonitoredSerialPort();
	size_t Read(void* Buffer, size_t Count) override;
	size_t Write(const void* Buffer, size_t Count) override;

	/** 0xB0 (scan) telegrams with a good CRC. */
	std::size_t goodScans() const { return m_goodScans; }
	/** Telegrams of any kind with a bad CRC. */
	std::size_t crcErrors() const { return m_crcErrors; }
	/** Oversized response headers blocked by the guard. */
	std::size_t blockedFrames() const { return m_blocked; }
	std::size_t skippedBytes() const;

private:
	/** Where the driver is after writing a command. */
	enum class Guard
	{
		Idle,    ///< not in a command exchange
		Ack,     ///< waiting for ACK (0x06)
		Frame,   ///< reading the response telegram
		Blocked  ///< oversized header seen: deliver nothing
	};
	void followByte(uint8_t b);

	mutable std::mutex m_mtx;
	lms2xx::TelegramParser m_parser;
	std::atomic<std::size_t> m_goodScans{0}, m_crcErrors{0}, m_blocked{0};
	Guard m_guard = Guard::Idle;
	std::size_t m_frameBytes = 0;
	uint8_t m_len[2] = {0, 0};
	std::chrono::steady_clock::time_point m_guardSince{};
};

}  // namespace semnav
