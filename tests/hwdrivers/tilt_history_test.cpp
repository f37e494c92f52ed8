/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <semnav/hwdrivers/TiltHeadModel.h>
#include <semnav/hwdrivers/TiltHistory.h>

#include <chrono>

using semnav::TiltHeadModel;
using semnav::TiltHistory;
using namespace std::chrono_literals;

TEST(TiltHistory, InterpolatesBetweenReportsAndWaitsForLaterOnes)
{
	TiltHistory h;
	const auto t0 = mrpt::Clock::now();
	h.add({t0, 0.0, true});
	h.add({t0 + 100ms, 0.1, true});
	double th = -1;
	ASSERT_EQ(h.tiltAt(t0 + 25ms, th), TiltHistory::Lookup::Ok);
	EXPECT_NEAR(th, 0.025, 1e-9);
	ASSERT_EQ(h.tiltAt(t0 + 100ms, th), TiltHistory::Lookup::Ok);
	EXPECT_NEAR(th, 0.1, 1e-12);
	EXPECT_EQ(h.tiltAt(t0 + 101ms, th), TiltHistory::Lookup::NotYet);
	EXPECT_EQ(h.tiltAt(t0 - 1ms, th), TiltHistory::Lookup::TooOld);
	// Out-of-order reports are ignored.
	h.add({t0 + 50ms, 5.0, true});
	ASSERT_EQ(h.tiltAt(t0 + 50ms, th), TiltHistory::Lookup::Ok);
	EXPECT_NEAR(th, 0.05, 1e-9);
}

TEST(TiltHistory, NoTiltWhileTheHeadIsRepositioned)
{
	TiltHistory h;
	const auto t0 = mrpt::Clock::now();
	h.add({t0, 0.0, true});
	h.add({t0 + 100ms, 0.1, false});
	h.add({t0 + 200ms, 0.2, true});
	h.add({t0 + 300ms, 0.3, true});
	double th = 0;
	EXPECT_EQ(h.tiltAt(t0 + 50ms, th), TiltHistory::Lookup::NotRecording);
	EXPECT_EQ(h.tiltAt(t0 + 150ms, th), TiltHistory::Lookup::NotRecording);
	EXPECT_EQ(h.tiltAt(t0 + 250ms, th), TiltHistory::Lookup::Ok);
	EXPECT_NEAR(th, 0.25, 1e-9);
}

TEST(TiltHistory, ForgetsOldSamples)
{
	TiltHistory h(1.0);
	const auto t0 = mrpt::Clock::now();
	for (int i = 0; i <= 30; i++) h.add({t0 + i * 100ms, 0.01 * i, true});
	double th = 0;
	EXPECT_EQ(h.tiltAt(t0 + 500ms, th), TiltHistory::Lookup::TooOld);
	EXPECT_EQ(h.tiltAt(t0 + 2500ms, th), TiltHistory::Lookup::Ok);
	EXPECT_LE(h.size(), 12u);
}

TEST(TiltHeadModel, MovesAtSpeedStopsAtTargetReportsWholeSteps)
{
	TiltHeadModel head(0.001, -1000, 1000);
	const auto t0 = TiltHeadModel::Clock::now();
	head.setSpeed(100, t0);
	head.moveTo(50, t0);
	EXPECT_NEAR(head.exactPosition(t0 + 250ms), 25.0, 1e-6);
	EXPECT_NEAR(head.angle(t0 + 250ms), 0.025, 1e-9);
	EXPECT_EQ(head.position(t0 + 254ms), 25);
	EXPECT_TRUE(head.moving(t0 + 400ms));
	EXPECT_EQ(head.position(t0 + 2s), 50);
	EXPECT_FALSE(head.moving(t0 + 2s));
	// New target mid-way: continues from where it is.
	head.moveTo(-50, t0 + 250ms);
	EXPECT_NEAR(head.exactPosition(t0 + 500ms), 0.0, 1e-6);
	head.halt(t0 + 500ms);
	EXPECT_EQ(head.position(t0 + 3s), 0);
}

TEST(TiltHistory, NoInterpolationAcrossLongGaps)
{
	TiltHistory h(10.0, 0.25);
	const auto t0 = mrpt::Clock::now();
	h.add({t0, 0.0, true});
	h.add({t0 + 200ms, 0.2, true});
	h.add({t0 + 800ms, 0.1, true});  // the head turned in between
	double th = 0;
	EXPECT_EQ(h.tiltAt(t0 + 100ms, th), TiltHistory::Lookup::Ok);
	EXPECT_EQ(h.tiltAt(t0 + 500ms, th), TiltHistory::Lookup::Gap);
	EXPECT_EQ(h.tiltAt(t0 + 800ms, th), TiltHistory::Lookup::Ok);
}
