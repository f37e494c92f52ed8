/* semnav: semantic navigation from tilting-laser sweeps */
// RawlogObjectReader: absurd counts are refused before anything is
// allocated, a damaged gzip stream is never taken for the end, empty and
// odometry-only rawlogs have no sweeps, the sensory-frame format still reads.
#include <gtest/gtest.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <semnav/common/Error.h>
#include <semnav/scan/RawlogObjectReader.h>
#include <semnav/scan/RawlogSweepReader.h>
#include <semnav/scan/RawlogWriter.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "ScanTestUtils.h"

using namespace semnav;
using semnav::test::makeLine;
using semnav::test::makeOdometry;
using semnav::test::tempDir;
namespace fs = std::filesystem;

namespace
{
/** Two nodding sweeps of 211 lines (odometry before each), plain. */
std::string writePlainLog(const fs::path& dir)
{
	const std::string path = (dir / "log.rawlog").string();
	RawlogWriter w(path, 0, RawlogWriter::Mode::Streaming);
	for (int n = 0; n < 2; n++)
	{
		w.write(*makeOdometry(n, 0, 0));
		for (int i = 0; i < 211; i++) w.write(*makeLine(n % 2 ? 210 - i : i));
	}
	w.commit();
	return path;
}

/** Byte offset of object `index` in a plain rawlog. */
std::uint64_t objectOffset(const std::string& path, std::size_t index)
{
	RawlogObjectReader r(path);
	mrpt::serialization::CSerializable::Ptr obj;
	while (r.objectsRead() < index && r.next(obj))
	{
	}
	return r.offset();
}

std::string readAll(const std::string& path)
{
	std::ifstream f(path, std::ios::binary);
	return std::string(std::istreambuf_iterator<char>(f), {});
}

void writeAll(const std::string& path, const std::string& data)
{
	std::ofstream(path, std::ios::binary | std::ios::trunc) << data;
}

/** The sweeps read before readRawlogSweeps' error, and its message. */
std::pair<std::vector<Sweep>, std::string> readUntilError(
    const std::string& path)
{
	RawlogSweepReader reader(path);
	std::vector<Sweep> got;
	Sweep s;
	try
	{
		while (reader.next(s)) got.push_back(s);
	}
	catch (const RawlogError& e)
	{
		return {got, e.what()};
	}
	return {got, ""};
}
}  // namespace

TEST(RawlogObjectReader, AbsurdBeamCountIsRefusedBeforeAllocating)
{
	const auto dir = tempDir("rawlog_beams");
	const auto path = writePlainLog(dir);
	// Object 250 is a line of the second sweep; its beam count follows the
	// sensor pose (a CPose3D object: name, version, 12 doubles, end flag).
	const std::uint64_t at = objectOffset(path, 250);
	std::string data = readAll(path);
	const auto pose = data.find("CPose3D", at);
	ASSERT_NE(pose, std::string::npos);
	const std::size_t countAt = pose + 7 + 1 + 12 * 8 + 1;
	std::uint32_t n;
	std::memcpy(&n, &data[countAt], 4);
	ASSERT_EQ(n, 361u) << "the scan layout changed";
	const std::uint32_t absurd = 0xfffffff0u;  // 4e9 beams: 36 GB
	std::memcpy(&data[countAt], &absurd, 4);
	writeAll(path, data);

	const auto [sweeps, msg] = readUntilError(path);
	ASSERT_EQ(sweeps.size(), 2u) << msg;  // the first + the cut one
	EXPECT_TRUE(sweeps[0].quality().complete);
	EXPECT_FALSE(sweeps[1].quality().complete);
	EXPECT_NE(msg.find(path), std::string::npos) << msg;
	EXPECT_NE(
	    msg.find("corrupt at object 250 (byte " + std::to_string(at)),
	    std::string::npos)
	    << msg;
	EXPECT_NE(msg.find("beams 4294967280 (at most 65536)"), std::string::npos)
	    << msg;
	EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
	fs::remove_all(dir);
}

TEST(RawlogObjectReader, DamagedGzipIsAnErrorNotTheEnd)
{
	const auto dir = tempDir("rawlog_gzflip");
	const std::string path = (dir / "log.rawlog").string();
	{
		RawlogWriter w(path, 1);
		for (int i = 0; i < 211; i++) w.write(*makeLine(i));
		w.commit();
	}
	std::string data = readAll(path);
	for (std::size_t k = 0; k < 64; k++) data[data.size() / 2 + k] ^= 0x5a;
	writeAll(path, data);
	const auto [sweeps, msg] = readUntilError(path);
	EXPECT_NE(msg.find(path + " is corrupt at object"), std::string::npos)
	    << msg;

	// Cut short: the gzip end is missing.
	writeAll(path, readAll(path).substr(0, data.size() / 3));
	EXPECT_NE(
	    readUntilError(path).second.find(" is truncated at object"),
	    std::string::npos);
	fs::remove_all(dir);
}

TEST(RawlogObjectReader, UnsupportedClassIsNamed)
{
	const auto dir = tempDir("rawlog_class");
	const std::string path = (dir / "log.rawlog").string();
	{
		RawlogWriter w(path, 1);
		w.write(*makeLine(0));
		w.write(mrpt::poses::CPose2D(1, 2, 3));
		w.commit();
	}
	RawlogObjectReader r(path);
	mrpt::serialization::CSerializable::Ptr obj;
	EXPECT_TRUE(r.next(obj));
	try
	{
		r.next(obj);
		FAIL() << "a CPose2D read as a rawlog object";
	}
	catch (const RawlogError& e)
	{
		const std::string msg = e.what();
		EXPECT_NE(msg.find("object 1 "), std::string::npos) << msg;
		EXPECT_NE(msg.find("CPose2D: unsupported class"), std::string::npos)
		    << msg;
	}
	EXPECT_FALSE(r.next(obj));
	fs::remove_all(dir);
}

TEST(RawlogSweepReader, EmptyAndOdometryOnlyRawlogsHaveNoSweeps)
{
	const auto dir = tempDir("rawlog_nosweeps");
	const std::string empty = (dir / "empty.rawlog").string();
	RawlogWriter(empty, 1).commit();
	const std::string odo = (dir / "odo.rawlog").string();
	{
		RawlogWriter w(odo, 1);
		for (int i = 0; i < 3; i++) w.write(*makeOdometry(i, 0, 0));
		w.commit();
	}
	for (const auto& [path, objects] : {std::pair{empty, 0}, std::pair{odo, 3}})
	{
		// The reader just ends (a replay has nothing to replay) ...
		EXPECT_EQ(readUntilError(path).first.size(), 0u);
		EXPECT_EQ(readUntilError(path).second, "");
		// ... readRawlogSweeps(), which needs sweeps, says so.
		try
		{
			readRawlogSweeps(path);
			ADD_FAILURE() << "no error for " << path;
		}
		catch (const RawlogError& e)
		{
			EXPECT_EQ(
			    std::string(e.what()), "no sweeps in " + path + " (" +
			                               std::to_string(objects) +
			                               " objects, 0 scan lines)");
		}
	}
	fs::remove_all(dir);
}

TEST(RawlogSweepReader, SensoryFrameFormatReads)
{
	const auto dir = tempDir("rawlog_sf");
	const std::string path = (dir / "sf.rawlog").string();
	{
		RawlogWriter w(path, 1);
		for (int n = 0; n < 2; n++)
		{
			mrpt::obs::CActionCollection acts;
			mrpt::obs::CActionRobotMovement2D mv;
			mrpt::obs::CActionRobotMovement2D::TMotionModelOptions model;
			if (n == 1)
			{
				model.modelSelection =
				    mrpt::obs::CActionRobotMovement2D::mmThrun;
				model.thrunModel.nParticlesCount = 50;
			}
			mv.computeFromOdometry(mrpt::poses::CPose2D(0.5, 0, 0), model);
			acts.insert(mv);
			w.write(acts);
			mrpt::obs::CSensoryFrame sf;
			for (int i = 0; i < 211; i++)
				sf.insert(makeLine(n % 2 ? 210 - i : i));
			w.write(sf);
		}
		w.commit();
	}
	const auto sweeps = readRawlogSweeps(path);
	ASSERT_EQ(sweeps.size(), 2u);
	EXPECT_TRUE(sweeps[1].quality().complete);
	EXPECT_EQ(sweeps[1].rows(), 211u);
	EXPECT_DOUBLE_EQ(sweeps[1].odometry().x(), 1.0);
	fs::remove_all(dir);
}
