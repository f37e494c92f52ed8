/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/system/crc.h>
#include <semnav/hwdrivers/Lms2xxTelegramParser.h>

#include <algorithm>
#include <stdexcept>

namespace semnav::lms2xx
{
uint16_t crc16(const uint8_t* data, std::size_t len)
{
	return mrpt::system::compute_CRC16(data, len, 0x8005);
}

std::vector<uint8_t> buildTelegram(
    uint8_t address, const std::vector<uint8_t>& payload)
{
	std::vector<uint8_t> t;
	t.reserve(payload.size() + 6);
	t.push_back(kStx);
	t.push_back(address);
	t.push_back(static_cast<uint8_t>(payload.size() & 0xFF));
	t.push_back(static_cast<uint8_t>(payload.size() >> 8));
	t.insert(t.end(), payload.begin(), payload.end());
	const uint16_t crc = crc16(t.data(), t.size());
	t.push_back(static_cast<uint8_t>(crc & 0xFF));
	t.push_back(static_cast<uint8_t>(crc >> 8));
	return t;
}

std::vector<uint8_t> buildMeasuredValues(
    const std::vector<uint16_t>& ranges_mm, bool mmMode)
{
	if (ranges_mm.size() > 0x1FF)
		throw std::invalid_argument("LMS2xx telegram: more than 511 ranges");
	std::vector<uint8_t> p;
	p.reserve(4 + 2 * ranges_mm.size());
	p.push_back(kCmdMeasuredValues);
	// Info word: bits 0-8 count, bits 14-15 unit (01 = mm).
	const uint16_t info =
	    static_cast<uint16_t>(ranges_mm.size() | (mmMode ? 0x4000 : 0x0000));
	p.push_back(static_cast<uint8_t>(info & 0xFF));
	p.push_back(static_cast<uint8_t>(info >> 8));
	for (uint16_t r : ranges_mm)
	{
		p.push_back(static_cast<uint8_t>(r & 0xFF));
		p.push_back(static_cast<uint8_t>(r >> 8));
	}
	p.push_back(0x10);  // status: no error
	return buildTelegram(kLmsAddress, p);
}

double lineRateLimit(int baud, std::size_t beams, double scanRateHz)
{
	const double link =
	    1.0 / transmissionTime(measuredValuesBytes(beams), baud);
	return std::min(link, scanRateHz);
}

void TelegramParser::reset()
{
	m_buf.clear();
	m_done.clear();
	m_doneHead = 0;
}

void TelegramParser::feed(const uint8_t* data, std::size_t n)
{
	for (std::size_t i = 0; i < n; i++)
	{
		const uint8_t b = data[i];
		const std::size_t k = m_buf.size();
		if (k == 0)
		{
			if (b == kStx)
				m_buf.push_back(b);
			else
				m_skipped++;
			continue;
		}
		if (k == 1)
		{
			if (b == m_address)
				m_buf.push_back(b);
			else
			{
				// The false STX is skipped; a new STX may start a telegram.
				m_skipped += b == kStx ? 1 : 2;
				m_buf.clear();
				if (b == kStx) m_buf.push_back(b);
			}
			continue;
		}
		m_buf.push_back(b);
		if (m_buf.size() < 4) continue;
		const std::size_t len = m_buf[2] | (m_buf[3] << 8);
		if (len + 6 > kMaxTelegram)
		{
			m_skipped += m_buf.size();
			m_buf.clear();
			continue;
		}
		if (m_buf.size() == len + 6)
		{
			Telegram t;
			t.bytes.swap(m_buf);
			const uint16_t crc = crc16(t.bytes.data(), len + 4);
			t.crcOk = (t.bytes[len + 4] | (t.bytes[len + 5] << 8)) == crc;
			m_done.push_back(std::move(t));
			m_buf.clear();
		}
	}
}

std::optional<Telegram> TelegramParser::next()
{
	if (m_doneHead >= m_done.size())
	{
		m_done.clear();
		m_doneHead = 0;
		return std::nullopt;
	}
	return std::move(m_done[m_doneHead++]);
}

std::vector<float> decodeMeasuredValues(const Telegram& t, bool* mmMode)
{
	std::vector<float> out;
	if (t.payloadSize() < 4 || t.command() != kCmdMeasuredValues) return out;
	const uint8_t* p = t.payload();
	const int info = p[1] | (p[2] << 8);
	const std::size_t n = info & 0x1FF;
	const bool mm = ((info & 0xC000) >> 14) != 0;
	if (mmMode) *mmMode = mm;
	if (3 + 2 * n + 1 > t.payloadSize()) return out;
	const int mask = mm ? 0x7FFF : 0x1FFF;
	const float scale = mm ? 0.001f : 0.01f;
	out.resize(n);
	for (std::size_t i = 0; i < n; i++)
		out[i] = ((p[3 + 2 * i] | (p[4 + 2 * i] << 8)) & mask) * scale;
	return out;
}

}  // namespace semnav::lms2xx
