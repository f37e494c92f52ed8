/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace semnav
{
/** SICK LMS2xx serial telegrams (LMS2xx "telegram listing"), as MRPT's
 * CSickLaserSerial sends and expects them:
 *
 *   STX(0x02) ADDR LEN_lo LEN_hi CMD DATA... [STATUS] CRC_lo CRC_hi
 *
 * LEN counts CMD .. STATUS; the CRC is mrpt::system::compute_CRC16 (the
 * LMS polynomial 0x8005) over STX .. STATUS. Host -> LMS telegrams use
 * ADDR 0x00, LMS -> host 0x80. */
namespace lms2xx
{
constexpr uint8_t kStx = 0x02;
constexpr uint8_t kAck = 0x06;
constexpr uint8_t kNack = 0x15;
constexpr uint8_t kHostAddress = 0x00;
constexpr uint8_t kLmsAddress = 0x80;
/** Continuous-output measured values (one scan line). */
constexpr uint8_t kCmdMeasuredValues = 0xB0;
/** Largest telegram MRPT accepts (its frame length limit). */
constexpr std::size_t kMaxTelegram = 806;
/** Bits on the wire per byte (start, 8 data, stop). */
constexpr double kBitsPerByte = 10.0;

/** CRC of the LMS2xx protocol. */
uint16_t crc16(const uint8_t* data, std::size_t len);

/** A whole telegram around `payload` (CMD, DATA and STATUS if any). */
std::vector<uint8_t> buildTelegram(
    uint8_t address, const std::vector<uint8_t>& payload);

/** A 0xB0 continuous-output telegram: `ranges_mm` (at most 511 values,
 * 13..15-bit codes) with the mm-unit flag set when `mmMode`; status 0x10. */
std::vector<uint8_t> buildMeasuredValues(
    const std::vector<uint16_t>& ranges_mm, bool mmMode);

/** Seconds a telegram of `bytes` takes on a serial line at `baud`. */
inline double transmissionTime(std::size_t bytes, int baud)
{
	return bytes * kBitsPerByte / baud;
}

/** Bytes of a 0xB0 telegram holding `n` ranges. */
inline std::size_t measuredValuesBytes(std::size_t n)
{
	return 10 + 2 * n;
}

/** Lines per second an LMS2xx can deliver: the scan rate (37.5 Hz for 0.5
 * deg interlaced, 75 Hz at 1 deg) or the serial link, whichever is lower. */
double lineRateLimit(int baud, std::size_t beams, double scanRateHz);

/** One telegram (see TelegramParser). */
struct Telegram
{
	std::vector<uint8_t> bytes;
	bool crcOk = false;
	uint8_t address() const { return bytes[1]; }
	uint8_t command() const { return bytes[4]; }
	/** Payload (CMD .. STATUS). */
	const uint8_t* payload() const { return bytes.data() + 4; }
	std::size_t payloadSize() const { return bytes.size() - 6; }
};

/** Ranges of a 0xB0 telegram in metres (empty if it is not one), with the
 * unit read from its info word as MRPT does. */
std::vector<float> decodeMeasuredValues(const Telegram& t, bool* mmMode);

}  // namespace lms2xx
}  // namespace semnav
