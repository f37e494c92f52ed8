/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <semnav/common/Error.h>
#include <semnav/scan/ThreeDtkReader.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "../common/ThreeDtkData.h"

using namespace semnav;
namespace fs = std::filesystem;

namespace
{
const fs::path& kDataDir = test::kThreeDtkDir;

struct RawXyz
{
	double x, y, z;
};
std::vector<RawXyz> readRaw(const fs::path& p)
{
	std::ifstream f(p);
	std::vector<RawXyz> out;
	RawXyz q;
	while (f >> q.x >> q.y >> q.z)
		out.push_back({q.x / 100, q.y / 100, q.z / 100});
	return out;
}
}  // namespace

TEST(ThreeDtkReader, ReadsTheOrganizedScanAndMasksInvalidReadings)
{
	SKIP_WITHOUT_3DTK("scan000.3d");
	const ThreeDtkReader reader;
	const Sweep s = reader.read((kDataDir / "scan000.3d").string());
	ASSERT_EQ(s.rows(), 226u);
	ASSERT_EQ(s.cols(), 360u);
	EXPECT_NEAR(s.theta(0) * 180 / M_PI, -48.7, 0.1);
	EXPECT_NEAR(s.theta(225) * 180 / M_PI, 67.6, 0.1);
	for (std::size_t r = 1; r < s.rows(); r++)
		EXPECT_GT(s.theta(r), s.theta(r - 1));
	EXPECT_NEAR(s.phi(0), -M_PI / 2, 1e-9);
	EXPECT_NEAR(s.phi(359), 89.5 * M_PI / 180, 1e-9);

	const auto raw = readRaw(kDataDir / "scan000.3d");
	ASSERT_EQ(raw.size(), 226u * 360u);
	std::size_t noReturn = 0, tooClose = 0, valid = 0;
	double maxErr = 0;
	for (std::size_t r = 0; r < s.rows(); r++)
		for (std::size_t c = 0; c < s.cols(); c++)
		{
			const auto& q = raw[r * 360 + c];
			const double rg = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z);
			if (rg >= 32.7)
			{
				noReturn++;
				EXPECT_FALSE(s.valid(r, c));
				continue;
			}
			if (rg < 0.5)
			{
				tooClose++;
				EXPECT_FALSE(s.valid(r, c));
				continue;
			}
			ASSERT_TRUE(s.valid(r, c));
			valid++;
			// Same point as the file's, in semnav's frame (x fwd, y left, z
			// up).
			const auto p = s.point(r, c);
			maxErr = std::max(
			    {maxErr, std::abs(p.x - q.z), std::abs(p.y + q.x),
			     std::abs(p.z - q.y)});
		}
	EXPECT_GT(noReturn, 0u);
	EXPECT_GT(tooClose, 0u);
	EXPECT_EQ(valid, s.validCount());
	EXPECT_LT(maxErr, 0.02)
	    << "per-row tilt does not reproduce the file's points";
}

TEST(ThreeDtkReader, FloorBelowTheSensorIsLevel)
{
	// What is known without labels: the lowest rows straight ahead see the
	// paved floor, so their points share one height.
	SKIP_WITHOUT_3DTK("scan000.3d");
	const Sweep s = ThreeDtkReader().read((kDataDir / "scan000.3d").string());
	std::vector<double> z;
	for (std::size_t r = 0; r < 20; r++)
		for (std::size_t c = 150; c < 210; c++)
			if (s.valid(r, c)) z.push_back(s.point(r, c).z);
	ASSERT_GT(z.size(), 500u);
	std::sort(z.begin(), z.end());
	const double median = z[z.size() / 2];
	const double iqr = z[z.size() * 3 / 4] - z[z.size() / 4];
	EXPECT_LT(median, -0.2) << "floor should be below the scanner";
	EXPECT_LT(iqr, 0.05) << "floor points should be level";
}

TEST(ThreeDtkReader, PoseFilesGiveTheSecondScanAhead)
{
	SKIP_WITHOUT_3DTK("scan001.pose");
	const auto p0 =
	    ThreeDtkReader::readPose((kDataDir / "scan000.pose").string());
	const auto p1 =
	    ThreeDtkReader::readPose((kDataDir / "scan001.pose").string());
	EXPECT_NEAR(p1.x() - p0.x(), 1.57, 0.05);
	EXPECT_NEAR(p1.y() - p0.y(), 0.03, 0.05);
	const Sweep s = ThreeDtkReader().read((kDataDir / "scan001.3d").string());
	ASSERT_TRUE(s.hasOdometry());
	EXPECT_NEAR(s.odometry().x(), p1.x(), 1e-9);
}

TEST(ThreeDtkReader, MalformedFilesNameTheLine)
{
	const fs::path p = fs::temp_directory_path() /
	                   ("semnav_bad_" + std::to_string(::getpid()) + ".3d");
	{
		std::ofstream f(p);
		f << "1 2 3\n4 five 6\n";
	}
	try
	{
		ThreeDtkReader().read(p.string());
		FAIL() << "malformed scan accepted";
	}
	catch (const IoError& e)
	{
		EXPECT_NE(std::string(e.what()).find(":2:"), std::string::npos)
		    << e.what();
	}
	{
		std::ofstream f(p);
		f << "1 2 3\n4 5 6\n";  // 2 points: not whole 360-beam lines
	}
	EXPECT_THROW(ThreeDtkReader().read(p.string()), IoError);
	EXPECT_THROW(ThreeDtkReader().read("/nonexistent/scan.3d"), IoError);
	fs::remove(p);
}
