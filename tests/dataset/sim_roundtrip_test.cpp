/* semnav: semantic navigation from tilting-laser sweeps */
// Round trip: scene -> semnav-sim (library) -> rawlog -> SweepAssembler,
// checked against the rawlog's own objects and the ground truth.
#include <gtest/gtest.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/serialization/CArchive.h>
#include <semnav/scan/RawlogSweepReader.h>
#include <semnav/scan/TiltGeometry.h>
#include <semnav/sim/SceneLoader.h>
#include <semnav/sim/SimulationRunner.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <regex>

using namespace semnav;
namespace fs = std::filesystem;

namespace
{
struct SimulatedOffice
{
	fs::path dir;
	Scene scene;
	SimulationResult result;
};

/** The bundled office, first three stops only, simulated once. */
const SimulatedOffice& office()
{
	static const SimulatedOffice sim = []
	{
		SimulatedOffice s;
		s.dir = fs::temp_directory_path() /
		        ("semnav_roundtrip_" + std::to_string(::getpid()));
		fs::remove_all(s.dir);
		s.scene = SceneLoader::loadFile(
		    std::string(SEMNAV_SOURCE_DIR) + "/datasets/office/office.yaml");
		s.scene.trajectory.resize(3);
		s.result = SimulationRunner(s.scene, SimulationRunner::TOptions(), 7)
		               .run(s.dir.string());
		return s;
	}();
	return sim;
}

/** The rawlog's objects, read without semnav's reader. */
struct RawContent
{
	std::vector<mrpt::obs::CObservation2DRangeScan::Ptr> scans;
	std::vector<mrpt::obs::CObservationOdometry::Ptr> odometry;
};
RawContent readRaw(const std::string& path)
{
	RawContent out;
	mrpt::io::CFileGZInputStream f(path);
	auto arch = mrpt::serialization::archiveFrom(f);
	for (;;)
	{
		mrpt::serialization::CSerializable::Ptr o;
		try
		{
			o = arch.ReadObject();
		}
		catch (const mrpt::serialization::CExceptionEOF&)
		{
			break;
		}
		if (auto s =
		        std::dynamic_pointer_cast<mrpt::obs::CObservation2DRangeScan>(
		            o))
			out.scans.push_back(s);
		else if (
		    auto d =
		        std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(o))
			out.odometry.push_back(d);
	}
	return out;
}

std::vector<std::array<double, 5>> readGt(const std::string& path)
{
	std::ifstream f(path);
	std::vector<std::array<double, 5>> out;
	std::string line;
	while (std::getline(f, line))
	{
		if (line.empty() || line[0] == '#') continue;
		std::istringstream is(line);
		std::array<double, 5> v{};
		is >> v[0] >> v[1] >> v[2] >> v[3] >> v[4];
		EXPECT_TRUE(is) << "bad gt line: " << line;
		out.push_back(v);
	}
	return out;
}
}  // namespace

TEST(SimRoundTrip, WritesTheFilesOfTheContract)
{
	const auto& s = office();
	EXPECT_EQ(s.result.sweeps, 3u);
	EXPECT_EQ(s.result.scans, 3u * 211u);
	EXPECT_TRUE(fs::exists(s.result.rawlogPath));
	EXPECT_EQ(readGt(s.result.gtPath).size(), 3u);
	for (int i = 0; i < 3; i++)
	{
		char name[32];
		std::snprintf(name, sizeof(name), "sweep_%04d.png", i);
		const cv::Mat img = cv::imread(
		    (fs::path(s.result.labelsDir) / name).string(),
		    cv::IMREAD_UNCHANGED);
		ASSERT_FALSE(img.empty()) << name;
		EXPECT_EQ(img.type(), CV_16UC1);
		EXPECT_EQ(img.rows, 211);
		EXPECT_EQ(img.cols, 361);
	}
	const RawContent raw = readRaw(s.result.rawlogPath);
	EXPECT_EQ(raw.scans.size(), 3u * 211u);
	EXPECT_EQ(raw.odometry.size(), 3u);
	for (const auto& sc : raw.scans)
	{
		ASSERT_EQ(sc->getScanSize(), 361u);
		EXPECT_EQ(sc->sensorLabel, "TILT_LMS");
		EXPECT_NEAR(sc->aperture, M_PI, 1e-6);
	}
}

TEST(SimRoundTrip, AssemblerGivesTheSameRangesAndTilts)
{
	const auto& s = office();
	const RawContent raw = readRaw(s.result.rawlogPath);
	const auto sweeps = readRawlogSweeps(s.result.rawlogPath);
	ASSERT_EQ(sweeps.size(), 3u);
	std::size_t line = 0;
	for (std::size_t k = 0; k < sweeps.size(); k++)
	{
		SCOPED_TRACE(k);
		const Sweep& sw = sweeps[k];
		ASSERT_EQ(sw.rows(), 211u);
		ASSERT_EQ(sw.cols(), 361u);
		EXPECT_TRUE(sw.quality().complete);
		EXPECT_EQ(sw.quality().missingLines, 0u);
		EXPECT_EQ(sw.quality().repeatedLines, 0u);
		EXPECT_EQ(sw.quality().ascending, k % 2 == 0);
		ASSERT_TRUE(sw.hasOdometry());
		EXPECT_EQ(sw.odometry(), raw.odometry[k]->odometry);
		for (std::size_t i = 0; i < 211; i++, line++)
		{
			const auto& sc = *raw.scans[line];
			const std::size_t r = sw.quality().ascending ? i : 210 - i;
			const double theta = tiltOfSensorPose(sc.sensorPose);
			ASSERT_NEAR(sw.theta(r), theta, 1e-9);
			ASSERT_NEAR(theta, (-15 + 0.5 * r) * M_PI / 180, 1e-9);
			for (std::size_t c = 0; c < 361; c++)
			{
				ASSERT_EQ(sw.valid(r, c), sc.getScanRangeValidity(c))
				    << r << "," << c;
				if (sw.valid(r, c))
					ASSERT_EQ(sw.range(r, c), sc.getScanRange(c));
			}
		}
	}
}

TEST(SimRoundTrip, LabelsAreThoseOfTheSurfacesHit)
{
	// Valid pixels carry a label, invalid ones none; floor and ceiling
	// points, placed in the world with the true pose, lie on their planes.
	const auto& s = office();
	const auto sweeps = readRawlogSweeps(s.result.rawlogPath);
	const auto gt = readGt(s.result.gtPath);
	const double ceiling = *s.scene.ceilingHeight;
	for (std::size_t k = 0; k < sweeps.size(); k++)
	{
		char name[32];
		std::snprintf(name, sizeof(name), "sweep_%04zu.png", k);
		const cv::Mat lab = cv::imread(
		    (fs::path(s.result.labelsDir) / name).string(),
		    cv::IMREAD_UNCHANGED);
		const mrpt::poses::CPose3D robot(gt[k][2], gt[k][3], 0, gt[k][4], 0, 0);
		std::map<int, std::size_t> seen;
		for (std::size_t r = 0; r < sweeps[k].rows(); r++)
			for (std::size_t c = 0; c < sweeps[k].cols(); c++)
			{
				const int v =
				    lab.at<uint16_t>(static_cast<int>(r), static_cast<int>(c));
				ASSERT_EQ(sweeps[k].valid(r, c), v != 0) << r << "," << c;
				if (!v) continue;
				const Label l = static_cast<Label>(v & 0xFF);
				seen[v & 0xFF]++;
				const auto p = sweeps[k].point(r, c);
				double wx, wy, wz;
				robot.composePoint(p.x, p.y, p.z, wx, wy, wz);
				if (l == Label::Floor) EXPECT_NEAR(wz, 0, 0.03);
				if (l == Label::Ceiling) EXPECT_NEAR(wz, ceiling, 0.03);
				if (l == Label::Floor || l == Label::Ceiling)
					EXPECT_EQ(v >> 8, 0);
				else
					EXPECT_GT(v >> 8, 0) << "object pixel without instance id";
			}
		EXPECT_GT(seen[static_cast<int>(Label::Floor)], 1000u);
		EXPECT_GT(seen[static_cast<int>(Label::Ceiling)], 1000u);
		EXPECT_GT(seen[static_cast<int>(Label::Wall)], 1000u);
	}
}

TEST(SimRoundTrip, MrptRawlogEditReadsTheRawlog)
{
	if (std::system("command -v rawlog-edit >/dev/null 2>&1") != 0)
		GTEST_SKIP()
		    << "MRPT's rawlog-edit is not installed (package mrpt-apps)";
	const auto& s = office();
	const std::string out = (s.dir / "info.txt").string();
	const std::string cmd = "rawlog-edit --info -i '" + s.result.rawlogPath +
	                        "' > '" + out + "' 2>&1";
	ASSERT_EQ(std::system(cmd.c_str()), 0) << "rawlog-edit failed, see " << out;
	std::ifstream f(out);
	std::stringstream ss;
	ss << f.rdbuf();
	const std::string text = ss.str();
	// MRPT 2.5's --info names sensors and counts objects: 3 odometry
	// entries and 3 x 211 scan lines, observation-only format.
	EXPECT_TRUE(std::regex_search(
	    text, std::regex("Overall number of objects\\s*:\\s*636")))
	    << text;
	EXPECT_TRUE(
	    std::regex_search(text, std::regex("Observations format\\s*:\\s*Yes")))
	    << text;
	EXPECT_TRUE(
	    std::regex_search(text, std::regex("TILT_LMS\\s*/\\s*633\\s*/")))
	    << text;
	EXPECT_TRUE(std::regex_search(text, std::regex("ODOMETRY\\s*/\\s*3\\s*/")))
	    << text;
}
