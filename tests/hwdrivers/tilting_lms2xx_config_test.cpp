/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <semnav/common/Error.h>
#include <semnav/hwdrivers/CTiltingLMS2xx.h>

#include <string>

#include "../common/SavedAndLoaded.h"

using semnav::CTiltingLMS2xx;

namespace
{
std::string shipped(const std::string& name)
{
	return std::string(SEMNAV_SOURCE_DIR) + "/config/" + name;
}

/** The error message of loading `ini`'s [TILT_LMS] through the sensor
 * (MRPT's CGenericSensor::loadConfig rewraps it with a backtrace). */
std::string loadError(const std::string& ini)
{
	mrpt::config::CConfigFileMemory cfg(ini);
	CTiltingLMS2xx s;
	try
	{
		s.loadConfig(cfg, "TILT_LMS");
	}
	catch (const std::exception& e)
	{
		return e.what();
	}
	return "";
}

const std::string kMinimal =
    "[TILT_LMS]\ndriver = CTiltingLMS2xx\nprocess_rate = 50\n"
    "COM_port_LIN = /dev/ttyUSB0\nptu_port = /dev/ttyUSB1\n";
}  // namespace

TEST(TiltingLms2xxConfig, ShippedRealHardwareFileLoads)
{
	mrpt::config::CConfigFile cfg(shipped("grabber-tilting-lms200.ini"));
	CTiltingLMS2xx s;
	s.loadConfig(cfg, "TILT_LMS");
	const auto& o = s.options();
	EXPECT_EQ(s.getSensorLabel(), "TILT_LMS");
	EXPECT_GT(s.getProcessRate(), 0);
	EXPECT_EQ(o.baudRate, 38400);
	EXPECT_EQ(o.ptuType, "dperception");
	EXPECT_EQ(o.ptuAxis, 'T');
	EXPECT_NEAR(o.thetaMin, -15 * M_PI / 180, 1e-12);
	EXPECT_NEAR(o.thetaMax, 90 * M_PI / 180, 1e-12);
	EXPECT_NEAR(o.mount.z, 0.45, 1e-12);
	// 361 ranges at 38400 baud: 38400 / 7320 lines/s.
	EXPECT_NEAR(s.lineRateLimit(), 38400.0 / 7320.0, 1e-9);
	EXPECT_EQ(cfg.read_string("TILT_LMS", "driver", ""), "CTiltingLMS2xx");
	EXPECT_FALSE(cfg.read_string("global", "rawlog_prefix", "").empty());
}

TEST(TiltingLms2xxConfig, ShippedEmulatorFileLoads)
{
	mrpt::config::CConfigFile cfg(shipped("grabber-emulated.ini"));
	CTiltingLMS2xx s;
	s.loadConfig(cfg, "TILT_LMS");
	EXPECT_EQ(s.options().baudRate, 500000);
	EXPECT_DOUBLE_EQ(s.lineRateLimit(), 37.5);
	// 0.5 deg per line at the LMS200's 37.5 lines/s.
	EXPECT_NEAR(
	    s.options().tiltSpeed / s.lineRateLimit(), 0.5 * M_PI / 180, 1e-9);
	EXPECT_FALSE(s.options().statsFile.empty());
	EXPECT_FALSE(cfg.read_bool("global", "use_sensoryframes", true));
}

TEST(TiltingLms2xxConfig, BadKeysAndValuesAreErrorsNamingThem)
{
	EXPECT_EQ(loadError(kMinimal), "");
	EXPECT_NE(
	    loadError(kMinimal + "tilt_sped_deg_s = 3\n").find("tilt_sped_deg_s"),
	    std::string::npos);
	EXPECT_NE(
	    loadError(kMinimal + "COM_baudRate = 57600\n").find("COM_baudRate"),
	    std::string::npos);
	EXPECT_NE(
	    loadError(kMinimal + "ptu_type = sony\n").find("ptu_type"),
	    std::string::npos);
	EXPECT_NE(
	    loadError(kMinimal + "theta_min_deg = 30\ntheta_max_deg = 20\n")
	        .find("theta_max_deg"),
	    std::string::npos);
	EXPECT_NE(
	    loadError(kMinimal + "resolution = 25\n").find("resolution"),
	    std::string::npos);
	EXPECT_NE(
	    loadError(
	        "[TILT_LMS]\nprocess_rate = 50\nCOM_port_LIN = /dev/ttyUSB0\n")
	        .find("ptu_port"),
	    std::string::npos);
}

TEST(TiltingLms2xxConfig, OptionsSaveAndLoadBack)
{
	CTiltingLMS2xx::TOptions a;
	a.lmsPort = "/dev/ttyS3";
	a.ptuPort = "/dev/ttyS4";
	a.baudRate = 500000;
	a.thetaMin = -0.2;
	a.tiltSpeed = 0.3;
	a.mount = {0.1, -0.05, 0.6};
	CTiltingLMS2xx::TOptions b = semnav::test::savedAndLoaded(a, "S");
	EXPECT_EQ(b.lmsPort, a.lmsPort);
	EXPECT_EQ(b.baudRate, 500000);
	EXPECT_NEAR(b.thetaMin, -0.2, 1e-6);
	EXPECT_NEAR(b.tiltSpeed, 0.3, 1e-6);
	EXPECT_NEAR(b.mount.y, -0.05, 1e-12);
}

TEST(TiltingLms2xxConfig, RegistersWithMrptsSensorFactory)
{
	CTiltingLMS2xx::doRegister();
	auto s = mrpt::hwdrivers::CGenericSensor::createSensorPtr("CTiltingLMS2xx");
	ASSERT_TRUE(s);
	EXPECT_NE(dynamic_cast<CTiltingLMS2xx*>(s.get()), nullptr);
}

TEST(TiltingLms2xxConfig, MissingHeadIsAClearErrorAndCleanShutdown)
{
	mrpt::config::CConfigFileMemory cfg(
	    "[TILT_LMS]\nprocess_rate = 50\nCOM_port_LIN = /nonexistent/lms\n"
	    "ptu_port = /nonexistent/ptu\n");
	std::string what;
	{
		CTiltingLMS2xx s;
		s.loadConfig(cfg, "TILT_LMS");
		try
		{
			s.initialize();
		}
		catch (const semnav::Error& e)
		{
			what = e.what();
		}
	}  // destroyed without a head: must not throw
	EXPECT_NE(what.find("/nonexistent/ptu"), std::string::npos) << what;
}
