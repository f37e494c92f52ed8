/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <semnav/emulation/PseudoTerminal.h>
#include <semnav/hwdrivers/Lms2xxTelegram.h>
#include <semnav/hwdrivers/MonitoredSerialPort.h>

#include <vector>

using namespace semnav;

namespace
{
/** Reads one byte at a time as MRPT's LMS_waitIncomingFrame() does. */
std::size_t readBytes(MonitoredSerialPort& port, std::size_t max)
{
	std::size_t got = 0;
	uint8_t b;
	for (std::size_t i = 0; i < max; i++)
		if (port.Read(&b, 1)) got++;
	return got;
}
}  // namespace

TEST(MonitoredSerialPort, CountsBadCrcAndBlocksOversizedResponseHeaders)
{
	PseudoTerminal pty;
	pty.open();
	MonitoredSerialPort port;
	port.setSerialPortName(pty.slavePath());
	port.open();
	port.setConfig(500000);
	port.setTimeouts(10, 0, 10, 0, 50);

	// A good response after a command goes through untouched.
	const uint8_t cmd[] = {0x02, 0x00, 0x01, 0x00, 0x31, 0x15, 0x12};
	port.Write(cmd, sizeof(cmd));
	std::vector<uint8_t> reply{lms2xx::kAck};
	const auto status =
	    lms2xx::buildTelegram(lms2xx::kLmsAddress, {0xB1, 0x10});
	reply.insert(reply.end(), status.begin(), status.end());
	pty.write(reply.data(), reply.size(), 0);
	EXPECT_EQ(readBytes(port, reply.size()), reply.size());
	EXPECT_EQ(port.blockedFrames(), 0u);

	// A false header announcing 65535 bytes: the driver would overrun its
	// 2000-byte buffer; the port delivers nothing after the header.
	port.Write(cmd, sizeof(cmd));
	std::vector<uint8_t> junk{lms2xx::kAck, 0x02, 0x13, 0x80, 0xFF, 0xFF};
	junk.resize(3000, 0x55);
	pty.write(junk.data(), junk.size(), 0);
	EXPECT_EQ(readBytes(port, 100), 6u);
	EXPECT_EQ(port.blockedFrames(), 1u);
	// The next command releases it.
	port.Write(cmd, sizeof(cmd));
	EXPECT_EQ(readBytes(port, 10), 10u);

	// Bad CRC on a scan telegram is counted (multi-byte reads, as the
	// continuous-output reader does).
	auto scan =
	    lms2xx::buildMeasuredValues(std::vector<uint16_t>(361, 900), true);
	port.purgeBuffers();
	scan[20] ^= 0xFF;
	pty.write(scan.data(), scan.size(), 0);
	const auto good =
	    lms2xx::buildMeasuredValues(std::vector<uint16_t>(361, 900), true);
	pty.write(good.data(), good.size(), 0);
	std::vector<uint8_t> buf(4000);
	std::size_t total = 0;
	for (int i = 0; i < 20 && total < scan.size() + good.size(); i++)
		total += port.Read(buf.data(), buf.size());
	EXPECT_EQ(port.crcErrors(), 1u);
	EXPECT_EQ(port.goodScans(), 1u);
}
