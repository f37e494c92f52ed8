/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/emulation/PtuEmulator.h>
#include <semnav/hwdrivers/TiltHeadModel.h>

#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdlib>

namespace semnav
{
namespace
{
constexpr int kBaud = 9600;

bool parseLong(const std::string& s, long& v)
{
	if (s.empty()) return false;
	char* end = nullptr;
	v = std::strtol(s.c_str(), &end, 10);
	return end && *end == '\0';
}
}  // namespace

PtuEmulator::PtuEmulator(TiltHeadModel& head, std::string linkPath)
    : mrpt::system::COutputLogger("PtuEmulator"),
      m_head(head),
      m_pty(std::move(linkPath))
{
}

PtuEmulator::~PtuEmulator()
{
	stop();
}

void PtuEmulator::start()
{
	m_pty.open();
	m_stop = false;
	m_thread = std::thread([this] { run(); });
}

void PtuEmulator::stop()
{
	m_stop = true;
	if (m_thread.joinable()) m_thread.join();
	m_pty.close();
}

std::string PtuEmulator::answer(const std::string& tokIn)
{
	std::string tok;
	for (char ch : tokIn) tok += static_cast<char>(std::toupper(ch));
	const auto now = TiltHeadModel::Clock::now();
	auto ok = [&](const std::string& text)
	{ return m_verbose && !text.empty() ? "* " + text : std::string("*"); };
	if (tok == "FV") return m_verbose = true, ok("");
	if (tok == "FT") return m_verbose = false, ok("");
	if (tok == "EE") return m_echo = true, ok("");
	if (tok == "ED") return m_echo = false, ok("");
	if (tok == "I" || tok == "S" || tok == "R" || tok == "LE" || tok == "LD")
		return ok("");
	if (tok == "V")
		return ok("Pan-Tilt Controller v2.12.4r(C46), semnav emulator");
	if (tok == "PR" || tok == "TR")
		return ok("185.1428 seconds arc per position");
	if (tok == "H" || tok == "HT")
	{
		m_head.halt(now);
		return ok("");
	}
	if (tok == "HP") return ok("");
	if (tok.size() < 2 || (tok[0] != 'P' && tok[0] != 'T'))
		return "! Illegal Command";
	const bool tilt = tok[0] == 'T';
	const std::string axis = tilt ? "Tilt" : "Pan";
	const char what = tok[1];
	const std::string arg = tok.substr(2);
	long v = 0;
	if (!arg.empty() && !parseLong(arg, v)) return "! Illegal Argument";
	switch (what)
	{
		case 'P':
		case 'O':
		{
			if (arg.empty())
				return ok(
				    "Current " + axis + " position is " +
				    std::to_string(tilt ? m_head.position(now) : 0L));
			if (!tilt) return ok("");
			const long target = what == 'O' ? m_head.target() + v : v;
			if (target > m_head.maxPosition())
				return "! Maximum allowable " + axis + " position is " +
				       std::to_string(m_head.maxPosition());
			if (target < m_head.minPosition())
				return "! Minimum allowable " + axis + " position is " +
				       std::to_string(m_head.minPosition());
			m_head.moveTo(target, now);
			return ok("");
		}
		case 'S':
			if (arg.empty())
				return ok(
				    "Target " + axis + " speed is " +
				    std::to_string(std::lround(m_head.speed())) +
				    " positions/sec");
			if (v <= 0 || v > 5000) return "! Value out of range";
			if (tilt) m_head.setSpeed(static_cast<double>(v), now);
			return ok("");
		case 'N':
			return ok(
			    "Minimum " + axis + " position is " +
			    std::to_string(m_head.minPosition()));
		case 'X':
			return ok(
			    "Maximum " + axis + " position is " +
			    std::to_string(m_head.maxPosition()));
		case 'A':
		case 'B':
		case 'U':
		case 'L':
			if (arg.empty()) return ok(axis + " value is 2000 positions/sec");
			return ok("");
		default:
			return "! Illegal Command";
	}
}

void PtuEmulator::run()
{
	std::string token;
	uint8_t buf[256];
	while (!m_stop)
	{
		const std::size_t n = m_pty.read(buf, sizeof(buf), 20);
		for (std::size_t i = 0; i < n; i++)
		{
			const char ch = static_cast<char>(buf[i]);
			if (ch != ' ' && ch != '\r' && ch != '\n')
			{
				if (token.size() < 64) token += ch;
				continue;
			}
			if (token.empty()) continue;
			m_commands++;
			if (token == "A" || token == "a")
			{
				// Await: answer when the tilt axis has stopped.
				while (!m_stop && m_head.moving(TiltHeadModel::Clock::now()))
					std::this_thread::sleep_for(std::chrono::milliseconds(5));
			}
			// The command's own line time at 9600 baud (the pseudo-terminal
			// delivers it at once).
			std::this_thread::sleep_for(std::chrono::duration<double>(
			    (token.size() + 1) * 10.0 / kBaud));
			std::string reply = answer(token);
			if (m_echo) reply = token + " " + reply;
			reply += "\r\n";
			m_pty.write(
			    reinterpret_cast<const uint8_t*>(reply.data()), reply.size(),
			    kBaud);
			token.clear();
		}
	}
}

}  // namespace semnav
