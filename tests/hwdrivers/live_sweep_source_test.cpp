/* semnav: semantic navigation from tilting-laser sweeps */
// LiveSweepSource without a laser: configuration errors, cancel() waking a
// blocked next(), and the DeviceLost end. An emulated PTU answers (the
// sensor needs its head); the laser's port has no device. The sweeps from
// the emulators are checked in tests/emulation.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/serialization/CArchive.h>
#include <semnav/common/Error.h>
#include <semnav/emulation/PtuEmulator.h>
#include <semnav/hwdrivers/LiveSweepSource.h>
#include <semnav/hwdrivers/TiltHeadModel.h>
#include <semnav/scan/RawlogSweepSource.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <future>
#include <thread>
#include <vector>

using namespace semnav;
using namespace std::chrono_literals;

namespace
{
namespace fs = std::filesystem;

const double kStep = mrpt::DEG2RAD(PtuEmulator::kArcSecPerPosition / 3600.0);

/** A [TILT_LMS] section nodding +-2 deg fast: a fault's recovery takes
 * 0.3 s, so device_lost_after_s may be short. */
std::string section(const std::string& lms, const std::string& ptu)
{
	return "[TILT_LMS]\n"
	       "driver = CTiltingLMS2xx\nprocess_rate = 50\n"
	       "COM_port_LIN = " +
	       lms + "\nCOM_baudRate = 500000\nptu_port = " + ptu +
	       "\ntheta_min_deg = -2\ntheta_max_deg = 2\ntilt_speed_deg_s = 40\n"
	       "stall_timeout_s = 0.1\nreconnect_delay_s = 0.1\n";
}

LiveSweepSource::TOptions quickLoss()
{
	LiveSweepSource::TOptions o;
	o.deviceLostAfter = 1.0;
	return o;
}

/** An emulated PTU and a laser port where nothing answers. */
struct LiveSweepSourceWithoutLaser : public ::testing::Test
{
	TiltHeadModel head{kStep, -2000, 2000};
	PtuEmulator ptu{head};
	std::string noLaser = (fs::temp_directory_path() /
	                       ("semnav_no_lms_" + std::to_string(::getpid())))
	                          .string();
	void SetUp() override { ptu.start(); }
	mrpt::config::CConfigFileMemory config()
	{
		return mrpt::config::CConfigFileMemory(
		    section(noLaser, ptu.devicePath()));
	}
};

std::string configError(
    const std::string& ini, const LiveSweepSource::TOptions& o)
{
	try
	{
		mrpt::config::CConfigFileMemory c(ini);
		LiveSweepSource s(c, "TILT_LMS", o);
	}
	catch (const std::exception& e)
	{
		return e.what();
	}
	return "";
}
}  // namespace

TEST(LiveSweepSourceConfig, BadSectionsNameTheKeyOrPort)
{
	const std::string ok = section("/nonexistent/lms", "/nonexistent/ptu");
	EXPECT_NE(
	    configError("[TILT_LMS]\nprocess_rate = 50\n", quickLoss())
	        .find("COM_port_LIN"),
	    std::string::npos);
	EXPECT_NE(
	    configError(ok + "bogus_key = 1\n", quickLoss()).find("bogus_key"),
	    std::string::npos);
	std::string noRate = ok;
	noRate.replace(noRate.find("process_rate = 50"), 17, "process_rate = 0");
	EXPECT_NE(
	    configError(noRate, quickLoss()).find("process_rate"),
	    std::string::npos);
	// Shorter than a fault's recovery (0.1 + 0.1 + 4 deg at 40 deg/s).
	auto o = quickLoss();
	o.deviceLostAfter = 0.25;
	EXPECT_NE(
	    configError(ok, o).find("device_lost_after_s"), std::string::npos);
	// The shipped configuration for the real devices (38400 baud, 45 s
	// sweeps) passes with the default (automatic) limit.
	mrpt::config::CConfigFile real(
	    std::string(SEMNAV_SOURCE_DIR) + "/config/grabber-tilting-lms200.ini");
	mrpt::config::CConfigFileMemory realIni;
	std::vector<std::string> keys;
	real.getAllKeys("TILT_LMS", keys);
	for (const auto& k : keys)
		realIni.write("TILT_LMS", k, real.read_string("TILT_LMS", k, ""));
	realIni.write("TILT_LMS", "ptu_port", "/nonexistent/ptu");
	std::string err;
	try
	{
		LiveSweepSource s(realIni, "TILT_LMS");
	}
	catch (const std::exception& e)
	{
		err = e.what();
	}
	EXPECT_NE(err.find("/nonexistent/ptu"), std::string::npos) << err;
	// Valid, but the head is not there.
	EXPECT_NE(
	    configError(ok, quickLoss()).find("/nonexistent/ptu"),
	    std::string::npos);
}

TEST_F(LiveSweepSourceWithoutLaser, CancelWakesABlockedNext)
{
	auto cfg = config();
	LiveSweepSource::TOptions o;
	o.deviceLostAfter = 60;
	LiveSweepSource source(cfg, "TILT_LMS", o);
	auto waiting = std::async(
	    std::launch::async,
	    [&]
	    {
		    Sweep s;
		    return source.next(s);
	    });
	EXPECT_EQ(waiting.wait_for(300ms), std::future_status::timeout);
	EXPECT_EQ(source.end(), SweepSource::End::None);
	const auto t0 = std::chrono::steady_clock::now();
	source.cancel();
	ASSERT_EQ(waiting.wait_for(2s), std::future_status::ready);
	EXPECT_FALSE(waiting.get());
	EXPECT_LT(std::chrono::steady_clock::now() - t0, 500ms);
	EXPECT_EQ(source.end(), SweepSource::End::Cancelled);
	EXPECT_NE(source.endMessage().find("cancelled"), std::string::npos);
	Sweep s;
	EXPECT_FALSE(source.next(s));
	EXPECT_EQ(source.linesReceived(), 0u);
}

TEST_F(
    LiveSweepSourceWithoutLaser,
    NoLaserEndsDeviceLostNamingThePortAndRecordingIsCommitted)
{
	auto cfg = config();
	auto o = quickLoss();
	o.recordPath =
	    (fs::temp_directory_path() /
	     ("semnav_live_lost_" + std::to_string(::getpid()) + ".rawlog"))
	        .string();
	fs::remove(o.recordPath);
	{
		LiveSweepSource source(cfg, "TILT_LMS", o);
		const auto t0 = std::chrono::steady_clock::now();
		Sweep s;
		EXPECT_FALSE(source.next(s));
		const double waited =
		    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0)
		        .count();
		EXPECT_GE(waited, 0.9);
		EXPECT_LT(waited, 3.0);
		EXPECT_EQ(source.end(), SweepSource::End::DeviceLost);
		const std::string msg = source.endMessage();
		EXPECT_NE(msg.find(noLaser), std::string::npos) << msg;
		EXPECT_NE(msg.find("device lost"), std::string::npos) << msg;
		EXPECT_NE(msg.find(ptu.devicePath()), std::string::npos) << msg;
		// cancel() after the end does not change why it ended.
		source.cancel();
		EXPECT_EQ(source.end(), SweepSource::End::DeviceLost);
		// Nothing under the final name until stop().
		EXPECT_FALSE(fs::exists(o.recordPath));
		EXPECT_EQ(source.odometryReadings(), 1u);
	}
	// The origin odometry, no line: a valid rawlog without sweeps.
	ASSERT_TRUE(fs::exists(o.recordPath));
	RawlogSweepSource back(o.recordPath);
	Sweep s;
	EXPECT_FALSE(back.next(s));
	EXPECT_EQ(back.end(), SweepSource::End::EndOfLog);
	EXPECT_EQ(back.reader().objectsRead(), 1u);
	fs::remove(o.recordPath);
}

TEST_F(LiveSweepSourceWithoutLaser, EveryNewOdometryReadingIsRecordedInOrder)
{
	auto cfg = config();
	LiveSweepSource::TOptions o;
	o.deviceLostAfter = 60;
	o.recordPath =
	    (fs::temp_directory_path() /
	     ("semnav_live_odo_" + std::to_string(::getpid()) + ".rawlog"))
	        .string();
	// A new reading every 4th poll (same time in between = not new).
	std::atomic<int> polls{0};
	const auto t0 = mrpt::Clock::now();
	auto provider = [&]
	{
		const int k = polls++ / 4;
		return LiveSweepSource::OdometryReading{
		    mrpt::poses::CPose2D(0.1 * k, 0, 0),
		    t0 + std::chrono::milliseconds(k)};
	};
	std::size_t readings = 0;
	{
		LiveSweepSource source(cfg, "TILT_LMS", o, provider);
		std::this_thread::sleep_for(600ms);
		source.stop();
		readings = source.odometryReadings();
		EXPECT_NEAR(readings, (polls + 3) / 4, 1.0);
		EXPECT_GE(readings, 5u);
	}
	mrpt::io::CFileGZInputStream in(o.recordPath);
	auto arch = mrpt::serialization::archiveFrom(in);
	std::vector<mrpt::obs::CObservationOdometry::Ptr> read;
	try
	{
		for (;;)
			read.push_back(
			    std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(
			        arch.ReadObject()));
	}
	catch (const mrpt::serialization::CExceptionEOF&)
	{
	}
	ASSERT_EQ(read.size(), readings);
	for (std::size_t i = 0; i < read.size(); i++)
	{
		ASSERT_TRUE(read[i]);
		EXPECT_NEAR(read[i]->odometry.x(), 0.1 * i, 1e-12);
		EXPECT_EQ(read[i]->timestamp, t0 + std::chrono::milliseconds(i));
	}
	fs::remove(o.recordPath);
}

TEST(LiveSweepSourceConfig, OwnKeysLoadAndUnknownOnesAreErrors)
{
	LiveSweepSource::TOptions o;
	o.loadFromConfigFile(
	    mrpt::config::CConfigFileMemory("[LIVE]\ndevice_lost_after_s = "
	                                    "20\nrecord_rawlog = /tmp/r.rawlog\n"),
	    "LIVE");
	EXPECT_EQ(o.deviceLostAfter, 20.0);
	EXPECT_EQ(o.recordPath, "/tmp/r.rawlog");
	try
	{
		o.loadFromConfigFile(
		    mrpt::config::CConfigFileMemory("[LIVE]\ndevice_lost_s = 1\n"),
		    "LIVE");
		ADD_FAILURE() << "unknown key accepted";
	}
	catch (const ConfigError& e)
	{
		EXPECT_NE(
		    std::string(e.what()).find("device_lost_s"), std::string::npos);
	}
	EXPECT_EQ(o.deviceLostAfter, 20.0);
}
