/* semnav: semantic navigation from tilting-laser sweeps */
#include <fcntl.h>
#include <poll.h>
#include <semnav/common/Error.h>
#include <semnav/emulation/PseudoTerminal.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <thread>

namespace semnav
{
namespace
{
int speedToBaud(speed_t s)
{
	switch (s)
	{
		case B1200:
			return 1200;
		case B2400:
			return 2400;
		case B4800:
			return 4800;
		case B9600:
			return 9600;
		case B19200:
			return 19200;
		case B38400:
			return 38400;
		case B57600:
			return 57600;
		case B115200:
			return 115200;
		case B230400:
			return 230400;
		case B460800:
			return 460800;
		case B500000:
			return 500000;
		default:
			return 0;
	}
}
}  // namespace

PseudoTerminal::PseudoTerminal(std::string linkPath)
    : m_link(std::move(linkPath))
{
}

PseudoTerminal::~PseudoTerminal()
{
	close();
}

void PseudoTerminal::open()
{
	close();
	const int m = ::posix_openpt(O_RDWR | O_NOCTTY | O_NONBLOCK);
	if (m < 0 || ::grantpt(m) != 0 || ::unlockpt(m) != 0)
	{
		if (m >= 0) ::close(m);
		throw IoError(
		    std::string("cannot create a pseudo-terminal: ") +
		    std::strerror(errno));
	}
	char name[128];
	if (::ptsname_r(m, name, sizeof(name)) != 0)
	{
		::close(m);
		throw IoError("ptsname failed");
	}
	// Keep a slave descriptor: the terminal survives clients closing it,
	// and its settings (the client's baud rate) can be read.
	const int s = ::open(name, O_RDWR | O_NOCTTY | O_NONBLOCK);
	if (s < 0)
	{
		::close(m);
		throw IoError(std::string("cannot open ") + name);
	}
	termios tio{};
	::tcgetattr(s, &tio);
	::cfmakeraw(&tio);
	::cfsetispeed(&tio, B9600);
	::cfsetospeed(&tio, B9600);
	::tcsetattr(s, TCSANOW, &tio);
	m_master = m;
	m_slave = s;
	m_slavePath = name;
	if (!m_link.empty())
	{
		const std::string tmp = m_link + ".tmp";
		::unlink(tmp.c_str());
		if (::symlink(name, tmp.c_str()) != 0 ||
		    ::rename(tmp.c_str(), m_link.c_str()) != 0)
			throw IoError(
			    "cannot link " + m_link + " to " + name + ": " +
			    std::strerror(errno));
	}
}

void PseudoTerminal::close()
{
	if (!m_link.empty() && m_master >= 0) ::unlink(m_link.c_str());
	if (m_slave >= 0) ::close(m_slave);
	if (m_master >= 0) ::close(m_master);
	m_slave = m_master = -1;
}

int PseudoTerminal::clientBaud() const
{
	if (m_slave < 0) return 0;
	termios tio{};
	if (::tcgetattr(m_slave, &tio) != 0) return 0;
	return speedToBaud(::cfgetospeed(&tio));
}

std::size_t PseudoTerminal::read(uint8_t* buf, std::size_t n, int timeoutMs)
{
	if (m_master < 0) return 0;
	pollfd p{m_master, POLLIN, 0};
	if (::poll(&p, 1, timeoutMs) <= 0 || !(p.revents & POLLIN)) return 0;
	const ssize_t r = ::read(m_master, buf, n);
	return r > 0 ? static_cast<std::size_t>(r) : 0;
}

std::size_t PseudoTerminal::write(const uint8_t* buf, std::size_t n, int baud)
{
	if (m_master < 0) return 0;
	using Clock = std::chrono::steady_clock;
	const auto t0 = Clock::now();
	// Chunks of about 2 ms of line time (at least 4 bytes), each handed over
	// when its last byte would have arrived on a real line; nothing waits
	// after the last one, so the device can answer the next command at
	// once (a UART is full duplex).
	const std::size_t chunk =
	    baud > 0 ? std::max<std::size_t>(4, baud / 10 / 500) : n;
	std::size_t done = 0;
	while (done < n)
	{
		const std::size_t k = std::min(chunk, n - done);
		if (baud > 0)
			std::this_thread::sleep_until(
			    t0 +
			    std::chrono::duration_cast<Clock::duration>(
			        std::chrono::duration<double>((done + k) * 10.0 / baud)));
		std::size_t sent = 0;
		const auto deadline = Clock::now() + std::chrono::milliseconds(200);
		while (sent < k)
		{
			const ssize_t w = ::write(m_master, buf + done + sent, k - sent);
			if (w > 0)
			{
				sent += static_cast<std::size_t>(w);
				continue;
			}
			if (w < 0 && errno != EAGAIN && errno != EINTR) return done;
			if (Clock::now() > deadline) return done + sent;  // not read
			pollfd p{m_master, POLLOUT, 0};
			::poll(&p, 1, 5);
		}
		done += k;
	}
	return done;
}

void PseudoTerminal::flushInput()
{
	if (m_master >= 0) ::tcflush(m_master, TCIFLUSH);
}

}  // namespace semnav
