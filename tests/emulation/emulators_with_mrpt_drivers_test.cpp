/* semnav: semantic navigation from tilting-laser sweeps */
// The emulators against MRPT's own drivers over pseudo-terminals: what the
// real CSickLaserSerial and CPtuDPerception send and expect, byte for byte.
#include <gtest/gtest.h>
#include <mrpt/hwdrivers/CPtuDPerception.h>
#include <mrpt/hwdrivers/CSickLaserSerial.h>
#include <semnav/emulation/LmsEmulator.h>
#include <semnav/emulation/PtuEmulator.h>
#include <semnav/emulation/SceneLineCaster.h>
#include <semnav/hwdrivers/MonitoredSerialPort.h>
#include <semnav/hwdrivers/TiltHeadModel.h>
#include <semnav/scan/TiltGeometry.h>
#include <semnav/sim/SceneLoader.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <thread>

using namespace semnav;
using namespace std::chrono_literals;

namespace
{
const double kStep = mrpt::DEG2RAD(PtuEmulator::kArcSecPerPosition / 3600.0);

Scene office()
{
	return SceneLoader::loadFile(
	    std::string(SEMNAV_SOURCE_DIR) + "/datasets/office/office.yaml");
}

/** First scan MRPT's driver delivers within `timeout`. */
bool readScan(
    mrpt::hwdrivers::CSickLaserSerial& lms,
    mrpt::obs::CObservation2DRangeScan& obs, std::chrono::milliseconds timeout)
{
	const auto end = std::chrono::steady_clock::now() + timeout;
	while (std::chrono::steady_clock::now() < end)
	{
		bool has = false, hw = false;
		lms.doProcessSimple(has, obs, hw);
		if (has) return true;
	}
	return false;
}
}  // namespace

TEST(PtuEmulator, AnswersInDirectedPerceptionSyntax)
{
	TiltHeadModel head(kStep, -100, 100);
	PtuEmulator ptu(head);
	EXPECT_EQ(ptu.answer("PR"), "* 185.1428 seconds arc per position");
	EXPECT_EQ(ptu.answer("TP50"), "*");
	EXPECT_EQ(ptu.answer("TP500"), "! Maximum allowable Tilt position is 100");
	EXPECT_EQ(
	    ptu.answer("TP-101"), "! Minimum allowable Tilt position is -100");
	EXPECT_EQ(ptu.answer("TS"), "* Target Tilt speed is 1000 positions/sec");
	EXPECT_EQ(ptu.answer("XYZ"), "! Illegal Command");
	EXPECT_EQ(ptu.answer("TPx"), "! Illegal Argument");
	EXPECT_EQ(ptu.answer("FT"), "*");
	EXPECT_EQ(ptu.answer("TN"), "*");  // terse mode: no text
}

TEST(PtuEmulator, MrptCPtuDPerceptionInitialisesMovesAndReadsPosition)
{
	TiltHeadModel head(kStep, -2000, 2000);
	PtuEmulator ptu(head);
	ptu.start();
	mrpt::hwdrivers::CPtuDPerception d;
	ASSERT_TRUE(d.init(ptu.devicePath()));
	EXPECT_NEAR(d.tiltResolution, kStep, 1e-9);
	ASSERT_TRUE(d.speed('T', mrpt::DEG2RAD(60.0)));
	EXPECT_NEAR(head.speed(), mrpt::DEG2RAD(60.0) / kStep, 1.0);
	ASSERT_TRUE(d.moveToAbsPos('T', mrpt::DEG2RAD(6.0)));
	double rad = 0, first = 0;
	ASSERT_TRUE(d.absPosQ('T', first));
	const auto end = std::chrono::steady_clock::now() + 2s;
	while (std::chrono::steady_clock::now() < end)
	{
		ASSERT_TRUE(d.absPosQ('T', rad));
		if (std::abs(rad - mrpt::DEG2RAD(6.0)) <= kStep) break;
	}
	EXPECT_LT(first, mrpt::DEG2RAD(6.0) - 2 * kStep);  // it was moving
	EXPECT_NEAR(rad, mrpt::DEG2RAD(6.0), kStep);
	// Out of the limits: the PTU says "!" and the driver reports failure.
	EXPECT_FALSE(d.moveToAbsPos('T', mrpt::DEG2RAD(150.0)));
	d.close();
	ptu.stop();
}

TEST(LmsEmulator, MrptCSickLaserSerialFindsBaudRateAndReadsTrueRanges)
{
	const Scene scene = office();
	const SceneLineCaster caster(scene);
	TiltHeadModel head(kStep, -2000, 2000);
	head.moveTo(
	    std::lround(mrpt::DEG2RAD(10.0) / kStep),
	    TiltHeadModel::Clock::now() - 10s);
	LmsEmulator::Options o;
	o.robotPose = scene.trajectory.front();
	o.powerOnBaud = 9600;  // as the LMS200 powers up
	LmsEmulator emu(caster, head, o);
	emu.start();

	auto port = std::make_shared<MonitoredSerialPort>();
	mrpt::hwdrivers::CSickLaserSerial lms;
	lms.setSerialPort(emu.devicePath());
	lms.setBaudRate(500000);
	lms.setMillimeterMode(true);
	lms.setScanResolution(50);
	lms.bindIO(port);
	ASSERT_NO_THROW(lms.initialize());
	mrpt::obs::CObservation2DRangeScan obs;
	ASSERT_TRUE(readScan(lms, obs, 2s));
	ASSERT_EQ(obs.getScanSize(), 361u);
	EXPECT_GT(port->goodScans(), 0u);
	EXPECT_EQ(port->crcErrors(), 0u);

	// Ranges = the scene cast at the head's tilt, within the noise.
	const double theta = head.angle(TiltHeadModel::Clock::now());
	std::vector<double> bearings(361);
	for (int i = 0; i < 361; i++) bearings[i] = mrpt::DEG2RAD(-90.0 + 0.5 * i);
	const auto truth = caster.cast(
	    o.robotPose, tiltedSensorPose(scene.sensor.mount, theta), bearings,
	    scene.sensor.maxRange);
	int compared = 0, close = 0;
	for (int i = 0; i < 361; i++)
	{
		if (truth[i] <= 0 || truth[i] > 7.9) continue;
		compared++;
		if (std::abs(obs.getScanRange(i) - truth[i]) < 5 * o.rangeNoise)
			close++;
	}
	EXPECT_GT(compared, 200);
	EXPECT_GE(close, compared * 98 / 100);
	EXPECT_GE(emu.counters().commands, 8u);
	emu.stop();
}

TEST(LmsEmulator, CorruptTelegramsAreDroppedByMrptAndCounted)
{
	const Scene scene = office();
	const SceneLineCaster caster(scene);
	TiltHeadModel head(kStep, -2000, 2000);
	LmsEmulator::Options o;
	o.robotPose = scene.trajectory.front();
	o.powerOnBaud = 500000;
	o.crcErrorRate = 1.0;
	LmsEmulator emu(caster, head, o);
	emu.start();
	auto port = std::make_shared<MonitoredSerialPort>();
	mrpt::hwdrivers::CSickLaserSerial lms;
	lms.setSerialPort(emu.devicePath());
	lms.setBaudRate(500000);
	lms.setMillimeterMode(true);
	lms.bindIO(port);
	ASSERT_NO_THROW(lms.initialize());
	mrpt::obs::CObservation2DRangeScan obs;
	EXPECT_FALSE(readScan(lms, obs, 600ms));
	EXPECT_GE(port->crcErrors(), 5u);
	EXPECT_EQ(port->goodScans(), 0u);
	EXPECT_GE(emu.counters().crcInjected, port->crcErrors());
	emu.stop();
}
