/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace semnav
{
/** The device side of a pseudo-terminal, standing in for a serial port.
 *
 * The client opens slavePath() (or the symlink `linkPath`, kept pointing at
 * the current terminal) as it would open /dev/ttyS0. close() is an unplug:
 * the client's reads fail (hang-up) and the device node disappears; open()
 * again plugs a new terminal in, under the same link. */
class PseudoTerminal
{
public:
	explicit PseudoTerminal(std::string linkPath = "");
	~PseudoTerminal();
	PseudoTerminal(const PseudoTerminal&) = delete;
	PseudoTerminal& operator=(const PseudoTerminal&) = delete;

	/** Creates the terminal (raw mode) and the link. Throws IoError. */
	void open();
	void close();
	bool isOpen() const { return m_master >= 0; }

	const std::string& slavePath() const { return m_slavePath; }
	const std::string& linkPath() const { return m_link; }
	/** The path a client should open: the link if any, else the slave. */
	std::string clientPath() const
	{
		return m_link.empty() ? m_slavePath : m_link;
	}

	/** The baud rate the client set on its side (0 if not a standard one). */
	int clientBaud() const;

	/** Reads what is there, waiting up to timeoutMs for the first byte;
	 * returns 0 on timeout. */
	std::size_t read(uint8_t* buf, std::size_t n, int timeoutMs);
	/** Writes all bytes, paced as a UART at `baud` (10 bits a byte) when
	 * baud > 0; bytes the client does not take within 0.2 s are lost, as
	 * on a real line. Returns the bytes delivered. */
	std::size_t write(const uint8_t* buf, std::size_t n, int baud);
	/** Discards pending input. */
	void flushInput();

private:
	std::string m_link, m_slavePath;
	int m_master = -1, m_slave = -1;
};

}  // namespace semnav
