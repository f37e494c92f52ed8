/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/system/COutputLogger.h>
#include <semnav/emulation/PseudoTerminal.h>

#include <atomic>
#include <string>
#include <thread>

namespace semnav
{
class TiltHeadModel;

/** A Directed Perception pan-tilt unit on a pseudo-terminal, speaking its
 * ASCII protocol as MRPT's CPtuDPerception uses it: commands are tokens
 * ended by a space, CR or LF ("TP", "TP-300", "TS364", "PR", "FV", "EE",
 * "I", "A", "H", ...); with echo on, each answer repeats the command, then
 * "*" (done, with text in verbose mode) or "!" (error), then CR LF, e.g.
 * "TP * Current Tilt position is -291". Answers are paced at 9600 baud.
 * The tilt axis moves the shared TiltHeadModel; the pan axis stays at 0. */
class PtuEmulator : public mrpt::system::COutputLogger
{
public:
	/** Resolution reported by PR/TR, seconds of arc per position. */
	static constexpr double kArcSecPerPosition = 185.1428;

	PtuEmulator(TiltHeadModel& head, std::string linkPath = "");
	~PtuEmulator();

	void start();
	void stop();
	std::string devicePath() const { return m_pty.clientPath(); }
	const std::string& slavePath() const { return m_pty.slavePath(); }
	std::size_t commands() const { return m_commands; }

	/** The answer to one command token (without the echo and CR LF);
	 * exposed for tests. */
	std::string answer(const std::string& token);

private:
	void run();

	TiltHeadModel& m_head;
	PseudoTerminal m_pty;
	std::thread m_thread;
	std::atomic<bool> m_stop{false};
	std::atomic<std::size_t> m_commands{0};
	bool m_echo = true, m_verbose = true;
	bool m_awaitPending = false;
	std::string m_awaitToken;
};

}  // namespace semnav
