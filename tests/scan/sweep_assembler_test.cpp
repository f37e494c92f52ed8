/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <semnav/common/Error.h>
#include <semnav/scan/SweepAssembler.h>

#include "../common/SavedAndLoaded.h"
#include "ScanTestUtils.h"

using namespace semnav;
using semnav::test::makeLine;
using semnav::test::makeOdometry;
using semnav::test::syntheticRange;

namespace
{
constexpr int kLines = 211;

/** Feeds sweep `n` of a nodding head: even sweeps go up, odd go down, each
 * with both end tilts (the end tilt repeats at the start of the next). */
void feedSweep(SweepAssembler& a, int n)
{
	for (int i = 0; i < kLines; i++)
		a.push(makeLine(n % 2 == 0 ? i : kLines - 1 - i));
}

std::vector<Sweep> drain(SweepAssembler& a)
{
	std::vector<Sweep> out;
	while (a.hasSweep()) out.push_back(a.pop());
	return out;
}

void expectRowsAreTiltIndices(const Sweep& s)
{
	ASSERT_EQ(s.rows(), static_cast<std::size_t>(kLines));
	ASSERT_EQ(s.cols(), 361u);
	for (std::size_t r = 0; r < s.rows(); r++)
	{
		EXPECT_NEAR(s.theta(r), (-15 + 0.5 * r) * M_PI / 180, 1e-9);
		if (s.valid(r, 100))  // rows of missing lines are all invalid
			EXPECT_FLOAT_EQ(
			    s.range(r, 100), syntheticRange(static_cast<int>(r), 100));
	}
}
}  // namespace

TEST(SweepAssembler, SplitsNoddingSweepsAtReversals)
{
	SweepAssembler a;
	for (int n = 0; n < 4; n++) feedSweep(a, n);
	a.finish();
	const auto sweeps = drain(a);
	ASSERT_EQ(sweeps.size(), 4u);
	for (std::size_t n = 0; n < sweeps.size(); n++)
	{
		SCOPED_TRACE(n);
		expectRowsAreTiltIndices(sweeps[n]);
		EXPECT_EQ(sweeps[n].quality().ascending, n % 2 == 0);
		EXPECT_TRUE(sweeps[n].quality().complete);
		EXPECT_EQ(sweeps[n].quality().missingLines, 0u);
		EXPECT_EQ(sweeps[n].quality().repeatedLines, 0u);
		EXPECT_EQ(sweeps[n].index(), n);
	}
}

TEST(SweepAssembler, PhiAndValidityFollowTheScan)
{
	SweepAssembler a;
	feedSweep(a, 0);
	a.finish();
	const Sweep s = a.pop();
	EXPECT_NEAR(s.phi(0), -M_PI / 2, 1e-6);
	EXPECT_NEAR(s.phi(180), 0, 1e-6);
	EXPECT_NEAR(s.phi(360), M_PI / 2, 1e-6);
	EXPECT_FALSE(s.valid(10, 7));
	EXPECT_FALSE(s.valid(10, 57));
	EXPECT_TRUE(s.valid(10, 8));
	EXPECT_EQ(s.validCount(), s.rows() * (361 - 8));
}

TEST(SweepAssembler, LeftToRightScansAreFlippedToRightFirst)
{
	SweepAssembler a;
	for (int k = 0; k < kLines; k++)
	{
		auto l = makeLine(k);
		l->rightToLeft = false;
		a.push(l);
	}
	a.finish();
	const Sweep s = a.pop();
	EXPECT_FLOAT_EQ(s.range(3, 0), syntheticRange(3, 360));
	EXPECT_FLOAT_EQ(s.range(3, 360), syntheticRange(3, 0));
}

TEST(SweepAssembler, MissingLinesBecomeInvalidRows)
{
	SweepAssembler a;
	for (int k = 0; k < kLines; k++)
		if (k != 50 && k != 51 && k != 120) a.push(makeLine(k));
	a.finish();
	const Sweep s = a.pop();
	expectRowsAreTiltIndices(s);
	EXPECT_EQ(s.quality().missingLines, 3u);
	EXPECT_EQ(s.validCount(), (s.rows() - 3) * (361 - 8));
	for (std::size_t c = 0; c < s.cols(); c++)
	{
		EXPECT_FALSE(s.valid(50, c));
		EXPECT_FALSE(s.valid(120, c));
	}
	EXPECT_TRUE(s.valid(52, 0));
	EXPECT_TRUE(s.quality().complete);
}

TEST(SweepAssembler, RepeatedLinesAreDroppedAndCounted)
{
	SweepAssembler a;
	for (int k = 0; k < kLines; k++)
	{
		a.push(makeLine(k));
		if (k == 30 || k == 31) a.push(makeLine(k));
	}
	a.finish();
	const auto sweeps = drain(a);
	ASSERT_EQ(sweeps.size(), 1u);
	expectRowsAreTiltIndices(sweeps[0]);
	EXPECT_EQ(sweeps[0].quality().repeatedLines, 2u);
}

// Found by fuzz_rawlog: a corrupt pose gave a NaN tilt, and the sweep's
// row count lround(NaN) made Sweep allocation throw std::length_error.
TEST(SweepAssembler, LinesWithNonFiniteTiltAreIgnored)
{
	SweepAssembler a;
	for (int k = 0; k < kLines; k++)
	{
		a.push(makeLine(k));
		if (k == 40)
		{
			auto bad = makeLine(k);
			bad->sensorPose.setYawPitchRoll(0, std::nan(""), 0);
			a.push(bad);
		}
	}
	a.finish();
	const auto sweeps = drain(a);
	ASSERT_EQ(sweeps.size(), 1u);
	expectRowsAreTiltIndices(sweeps[0]);
}

TEST(SweepAssembler, TinyTiltGapsDoNotSizeTheSweepWithoutBound)
{
	SweepAssembler::TOptions o;
	o.sameTiltTolerance = 0;
	SweepAssembler a(o);
	// Lines 1e-12 rad apart, then one 0.2 rad further: the median gap
	// alone would give 2e11 rows.
	for (int k = 0; k < 10; k++) a.push(makeLine(k, 0, 1e-12));
	a.push(makeLine(1, 0.1, 0.1));
	a.finish();
	const auto sweeps = drain(a);
	ASSERT_EQ(sweeps.size(), 1u);
	EXPECT_LE(sweeps[0].rows(), 4u * 11);
	EXPECT_GE(sweeps[0].rows(), 2u);
}

TEST(SweepAssembler, IncompleteLastSweepIsReportedNotDropped)
{
	SweepAssembler a;
	feedSweep(a, 0);
	feedSweep(a, 1);
	for (int k = 0; k < 80; k++) a.push(makeLine(k));  // cut short
	a.finish();
	const auto sweeps = drain(a);
	ASSERT_EQ(sweeps.size(), 3u);
	EXPECT_TRUE(sweeps[0].quality().complete);
	EXPECT_TRUE(sweeps[1].quality().complete);
	EXPECT_FALSE(sweeps[2].quality().complete);
	EXPECT_EQ(sweeps[2].rows(), 80u);
}

TEST(SweepAssembler, OdometryIsAttachedAndMotionEndsASweep)
{
	SweepAssembler a;
	a.push(makeOdometry(1, 2, 0.1));
	for (int k = 0; k < 100; k++) a.push(makeLine(k));
	a.push(makeOdometry(1, 2, 0.1));  // same pose: no split
	for (int k = 100; k < kLines; k++) a.push(makeLine(k));
	a.push(makeOdometry(3, 2, 0.1));  // moved: sweep 0 ends
	for (int k = 0; k < kLines; k++) a.push(makeLine(k));  // up again
	a.finish();
	const auto sweeps = drain(a);
	ASSERT_EQ(sweeps.size(), 2u);
	expectRowsAreTiltIndices(sweeps[0]);
	expectRowsAreTiltIndices(sweeps[1]);
	ASSERT_TRUE(sweeps[0].hasOdometry());
	EXPECT_DOUBLE_EQ(sweeps[0].odometry().x(), 1);
	EXPECT_DOUBLE_EQ(sweeps[1].odometry().x(), 3);
	EXPECT_TRUE(sweeps[1].quality().ascending);
}

TEST(SweepAssembler, OtherSensorsAreIgnored)
{
	SweepAssembler a;
	for (int k = 0; k < kLines; k++)
	{
		a.push(makeLine(k));
		a.push(makeLine(
		    kLines - 1 - k, -15 * M_PI / 180, 0.5 * M_PI / 180, 361,
		    "FRONT_LASER"));
	}
	a.finish();
	const auto sweeps = drain(a);
	ASSERT_EQ(sweeps.size(), 1u);
	expectRowsAreTiltIndices(sweeps[0]);
	EXPECT_EQ(a.linesIgnored(), static_cast<std::size_t>(kLines));
}

TEST(SweepAssembler, PointsAreInTheRobotFrame)
{
	SweepAssembler a;
	feedSweep(a, 0);
	a.finish();
	const Sweep s = a.pop();
	const std::size_t r = 100, c = 180;  // phi = 0
	const auto p = s.point(r, c);
	const double th = s.theta(r), rg = s.range(r, c);
	EXPECT_NEAR(p.x, rg * std::cos(th), 1e-5);
	EXPECT_NEAR(p.y, 0, 1e-5);
	EXPECT_NEAR(p.z, 0.45 + rg * std::sin(th), 1e-5);
	const auto all = s.points();
	ASSERT_EQ(all.size(), s.rows() * s.cols());
	EXPECT_TRUE(std::isnan(all[r * s.cols() + 7].x));
	EXPECT_FLOAT_EQ(all[r * s.cols() + c].x, p.x);
}

TEST(SweepAssemblerOptions, LoadSaveAndRejectBadKeys)
{
	SweepAssembler::TOptions o;
	o.minValidRange = 0.3;
	o.splitOnMotion = false;
	SweepAssembler::TOptions back = test::savedAndLoaded(o, "SweepAssembler");
	EXPECT_DOUBLE_EQ(back.minValidRange, 0.3);
	EXPECT_FALSE(back.splitOnMotion);
	EXPECT_NEAR(back.sameTiltTolerance, o.sameTiltTolerance, 1e-12);

	mrpt::config::CConfigFileMemory bad(
	    "[SweepAssembler]\nmin_valid_rang_m = 0.3\n");
	EXPECT_THROW(back.loadFromConfigFile(bad, "SweepAssembler"), ConfigError);
	mrpt::config::CConfigFileMemory range(
	    "[SweepAssembler]\ncomplete_span_fraction = 1.5\n");
	try
	{
		back.loadFromConfigFile(range, "SweepAssembler");
		FAIL() << "out-of-range value accepted";
	}
	catch (const ConfigError& e)
	{
		EXPECT_NE(
		    std::string(e.what()).find("complete_span_fraction"),
		    std::string::npos);
	}
}
