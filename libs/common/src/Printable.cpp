/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/Printable.h>

#include <cstdint>
#include <cstdio>

namespace semnav
{
namespace
{
/** Length of the valid, printable UTF-8 sequence at `s[i]` (>= 2 bytes),
 * or 0. */
std::size_t printableSequence(const std::string& s, std::size_t i)
{
	const auto at = [&](std::size_t k)
	{ return k < s.size() ? static_cast<uint8_t>(s[k]) : uint8_t(0); };
	const uint8_t b = at(i);
	std::size_t n = 0;
	uint8_t lo = 0x80, hi = 0xBF;  // range of the second byte
	if (b >= 0xC2 && b <= 0xDF)
		n = 2;
	else if (b >= 0xE0 && b <= 0xEF)
	{
		n = 3;
		lo = b == 0xE0 ? 0xA0 : 0x80;  // no overlong forms
		hi = b == 0xED ? 0x9F : 0xBF;  // no surrogates
	}
	else if (b >= 0xF0 && b <= 0xF4)
	{
		n = 4;
		lo = b == 0xF0 ? 0x90 : 0x80;
		hi = b == 0xF4 ? 0x8F : 0xBF;
	}
	else
		return 0;
	if (at(i + 1) < lo || at(i + 1) > hi) return 0;
	for (std::size_t k = 2; k < n; k++)
		if (at(i + k) < 0x80 || at(i + k) > 0xBF) return 0;
	if (b == 0xC2 && at(i + 1) <= 0x9F) return 0;  // C1 controls
	return n;
}
}  // namespace

std::string printable(const std::string& text)
{
	std::string out;
	out.reserve(text.size());
	for (std::size_t i = 0; i < text.size();)
	{
		const auto b = static_cast<uint8_t>(text[i]);
		if (b >= 0x20 && b < 0x7F)
		{
			out += text[i++];
			continue;
		}
		if (const std::size_t n = printableSequence(text, i))
		{
			out.append(text, i, n);
			i += n;
			continue;
		}
		char hex[5];
		std::snprintf(hex, sizeof(hex), "\\x%02X", b);
		out += hex;
		i++;
	}
	return out;
}

}  // namespace semnav
