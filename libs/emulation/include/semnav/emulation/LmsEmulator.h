/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/math/TPose2D.h>
#include <mrpt/system/COutputLogger.h>
#include <semnav/emulation/PseudoTerminal.h>

#include <atomic>
#include <cstdint>
#include <fstream>
#include <functional>
#include <random>
#include <string>
#include <thread>

namespace semnav
{
class SceneLineCaster;
class TiltHeadModel;

/** A SICK LMS200 on a pseudo-terminal, speaking the LMS2xx telegram
 * protocol as MRPT's CSickLaserSerial uses it: status (0x31), operating
 * modes (0x20: installation with password, monitoring 0x25, continuous
 * output 0x24, baud rates 0x40/0x42/0x48), configuration (0x74/0x77, mm
 * mode), angle and resolution (0x3B), ACK/NACK and CRC16 on everything.
 *
 * It powers up at 9600 baud and answers only when the client's port is at
 * its rate (read from the terminal's settings), so MRPT's baud-rate
 * detection runs as on the real device. In continuous mode it scans at
 * 75 Hz / interlacing (37.5 lines/s at 0.5 deg) and sends the newest scan
 * whenever the line is free, paced at the baud rate; each scan is cast
 * through the scene at the head's angle at scan time, with Gaussian range
 * noise, in mm (or cm) with 8191 as the no-return code.
 *
 * Faults: CRC errors and dropped bytes (per telegram probabilities),
 * one stall (silence, input ignored) and one disconnect (terminal closed,
 * re-created under the same link after a while, powered up again). */
class LmsEmulator : public mrpt::system::COutputLogger
{
public:
	struct Options
	{
		std::string linkPath;  ///< symlink to the terminal; empty = none
		int powerOnBaud = 9600;
		mrpt::math::TPose2D robotPose;
		/** When set, the robot's true pose at each scan (a moving base,
		 * e.g. EmulatedDiffDriveBase::truePose); robotPose otherwise. */
		std::function<mrpt::math::TPose2D()> poseSource;
		double rangeNoise = 0.005;  ///< m
		double maxRange = 8.0;      ///< m; beyond: no return
		uint64_t seed = 1;
		double crcErrorRate = 0;  ///< fraction of scan telegrams corrupted
		double dropByteRate = 0;  ///< fraction losing one byte
		/** Seconds after the first continuous output; < 0 = never. */
		double stallAt = -1, stallFor = 0;
		double disconnectAt = -1, disconnectFor = 0;
		/** When set, one line per scan sent: wall-clock time (s since the
		 * epoch) of the scan and the head's true tilt (rad). */
		std::string truthLog;
	};
	struct Counters
	{
		std::size_t scansSent = 0, crcInjected = 0, bytesDropped = 0;
		std::size_t commands = 0, nacks = 0, stalls = 0, disconnects = 0;
	};

	LmsEmulator(
	    const SceneLineCaster& caster, const TiltHeadModel& head,
	    const Options& options);
	~LmsEmulator();

	/** Opens the terminal and starts serving. Throws IoError. */
	void start();
	void stop();
	/** Path for the client (link or /dev/pts/N). */
	std::string devicePath() const { return m_pty.clientPath(); }
	const std::string& slavePath() const { return m_pty.slavePath(); }
	Counters counters() const;

private:
	void run();
	void handle(const std::vector<uint8_t>& payload);
	void respond(const std::vector<uint8_t>& payload);
	void sendScan();
	void powerOn();

	const SceneLineCaster& m_caster;
	const TiltHeadModel& m_head;
	Options m_opt;
	PseudoTerminal m_pty;
	std::thread m_thread;
	std::atomic<bool> m_stop{false};
	std::mt19937_64 m_rng;
	std::ofstream m_truth;

	// Device state.
	int m_baud = 9600;
	int m_pendingBaud = 0;
	bool m_mm = false, m_continuous = false;
	int m_fov = 180, m_res = 100;

	mutable std::mutex m_cmtx;
	Counters m_counters;
};

}  // namespace semnav
