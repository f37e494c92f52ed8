/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/hwdrivers/Lms2xxTelegram.h>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace semnav::lms2xx
{
/** Splits a byte stream into telegrams with the same resynchronisation rule
 * as CSickLaserSerial (a telegram starts with STX followed by `address`; a
 * length over kMaxTelegram is a false start). Lone ACK/NACK bytes between
 * telegrams are skipped. */
class TelegramParser
{
public:
	explicit TelegramParser(uint8_t address) : m_address(address) {}
	/** Feeds bytes; complete telegrams are queued for next(). */
	void feed(const uint8_t* data, std::size_t n);
	/** Next complete telegram, if any. */
	std::optional<Telegram> next();
	/** Bytes skipped while hunting for a telegram start. */
	std::size_t skippedBytes() const { return m_skipped; }
	void reset();

private:
	uint8_t m_address;
	std::vector<uint8_t> m_buf;
	std::vector<Telegram> m_done;
	std::size_t m_doneHead = 0;
	std::size_t m_skipped = 0;
};

}  // namespace semnav::lms2xx
