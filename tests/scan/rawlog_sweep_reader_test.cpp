/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <semnav/common/Error.h>
#include <semnav/scan/RawlogSweepReader.h>
#include <semnav/scan/RawlogWriter.h>

#include <filesystem>
#include <fstream>

#include "ScanTestUtils.h"

using namespace semnav;
using semnav::test::makeLine;
using semnav::test::makeOdometry;
using semnav::test::syntheticRange;
using semnav::test::tempDir;
namespace fs = std::filesystem;

namespace
{
/** Writes `sweeps` nodding sweeps of 211 lines, odometry before each. */
std::string writeLog(const fs::path& dir, int sweeps, int compress = 1)
{
	const std::string path = (dir / "log.rawlog").string();
	RawlogWriter w(path, compress);
	for (int n = 0; n < sweeps; n++)
	{
		w.write(*makeOdometry(n, 0, 0));
		for (int i = 0; i < 211; i++)
			w.write(*makeLine(n % 2 == 0 ? i : 210 - i));
	}
	w.commit();
	return path;
}
}  // namespace

TEST(RawlogSweepReader, ReadsBackWhatWasWritten)
{
	const auto dir = tempDir("rawlog_rt");
	const auto path = writeLog(dir, 3);
	RawlogSweepReader reader(path);
	Sweep s;
	int n = 0;
	while (reader.next(s))
	{
		ASSERT_EQ(s.rows(), 211u);
		EXPECT_TRUE(s.quality().complete);
		EXPECT_DOUBLE_EQ(s.odometry().x(), n);
		EXPECT_FLOAT_EQ(s.range(17, 3), syntheticRange(17, 3));
		EXPECT_NEAR(s.theta(17), (-15 + 0.5 * 17) * M_PI / 180, 1e-6);
		n++;
	}
	EXPECT_EQ(n, 3);
	EXPECT_EQ(reader.objectsRead(), 3u * 212u);
	fs::remove_all(dir);
}

TEST(RawlogSweepReader, TruncatedLogGivesGoodSweepsThenAClearError)
{
	const auto dir = tempDir("rawlog_trunc");
	const auto path = writeLog(dir, 3, 0);  // uncompressed: cut is exact
	const auto size = fs::file_size(path);
	fs::resize_file(path, size * 5 / 6);  // inside sweep 2
	RawlogSweepReader reader(path);
	Sweep s;
	std::vector<Sweep> got;
	try
	{
		while (reader.next(s)) got.push_back(s);
		FAIL() << "truncated rawlog read without error";
	}
	catch (const RawlogError& e)
	{
		const std::string msg = e.what();
		EXPECT_NE(msg.find(path), std::string::npos) << msg;
		EXPECT_NE(msg.find("is truncated at object"), std::string::npos) << msg;
		EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
	}
	ASSERT_EQ(got.size(), 3u);
	EXPECT_TRUE(got[0].quality().complete);
	EXPECT_TRUE(got[1].quality().complete);
	EXPECT_FALSE(got[2].quality().complete);
	fs::remove_all(dir);
}

TEST(RawlogSweepReader, LiveRecordingGivesTheStandingSweepsOnly)
{
	const auto dir = tempDir("rawlog_live");
	const std::string path = (dir / "robot.rawlog").string();
	const double stoppedAt = test::writeStopAndScanRecording(path);

	// The live source's options keep the pieces, all incomplete: the same
	// three sweeps are complete.
	std::size_t complete = 0;
	for (const Sweep& sweep : readRawlogSweeps(path))
		complete += sweep.quality().complete ? 1 : 0;
	EXPECT_EQ(complete, 3u);

	RawlogSweepReader reader(path, SweepAssembler::TOptions::forRecordings());
	std::vector<Sweep> got;
	Sweep s;
	EXPECT_NO_THROW(while (reader.next(s)) got.push_back(s));
	// The piece the log ends in is flagged incomplete (semnav-map and the
	// robot skip those), the other pieces taken while driving are dropped.
	ASSERT_EQ(got.size(), 4u);
	EXPECT_FALSE(got.back().quality().complete);
	got.pop_back();
	for (const Sweep& sweep : got)
	{
		EXPECT_TRUE(sweep.quality().complete);
		EXPECT_EQ(sweep.rows(), 211u);
	}
	EXPECT_EQ(got[1].quality().missingLines, 21u);
	EXPECT_DOUBLE_EQ(got[0].odometry().x(), 0);
	EXPECT_DOUBLE_EQ(got[1].odometry().x(), 0);
	EXPECT_NEAR(got[2].odometry().x(), stoppedAt, 1e-12);
	EXPECT_GT(stoppedAt, 0.1);
	EXPECT_EQ(got[2].index(), 2u);  // dropped pieces take no index
	EXPECT_GT(reader.assembler().sweepsDroppedMoving(), 10u);
	fs::remove_all(dir);
}

TEST(RawlogSweepReader, GarbageAndMissingFilesAreRawlogErrors)
{
	const auto dir = tempDir("rawlog_bad");
	const auto garbage = (dir / "garbage.rawlog").string();
	std::ofstream(garbage) << "this is not a rawlog at all, just text\n";
	EXPECT_THROW(readRawlogSweeps(garbage), RawlogError);
	EXPECT_THROW(
	    readRawlogSweeps((dir / "missing.rawlog").string()), RawlogError);
	fs::remove_all(dir);
}

TEST(RawlogWriter, UncommittedWriterLeavesNoFile)
{
	const auto dir = tempDir("rawlog_atomic");
	const auto path = (dir / "a.rawlog").string();
	{
		RawlogWriter w(path);
		w.write(*makeLine(0));
	}
	EXPECT_FALSE(fs::exists(path));
	EXPECT_TRUE(fs::is_empty(dir)) << "temporary file left behind";
	fs::remove_all(dir);
}

// Inputs on which fuzz_rawlog (fuzz/) crashed: each must read to its end or
// to a RawlogError, nothing else.
TEST(RawlogSweepReader, FuzzCrashInputsEndInSweepsOrRawlogError)
{
	for (const char* name : {"fuzz-rawlog-nan-tilt.rawlog"})
	{
		SCOPED_TRACE(name);
		const std::string path =
		    std::string(SEMNAV_SOURCE_DIR) + "/tests/scan/data/" + name;
		ASSERT_TRUE(fs::exists(path));
		try
		{
			RawlogSweepReader reader(path);
			Sweep s;
			while (reader.next(s))
			{
			}
		}
		catch (const RawlogError&)
		{
		}
	}
}
