/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <semnav/perception/PerceptionPipeline.h>
#include <semnav/scan/ThreeDtkReader.h>

#include <cstdio>
#include <filesystem>

#include "../common/ThreeDtkData.h"

using namespace semnav;
namespace fs = std::filesystem;

namespace
{
const fs::path& kDataDir = test::kThreeDtkDir;

/** Fraction of valid pixels in rows [r0, r1) x cols [c0, c1) labelled l. */
double fraction(
    const LabeledSweep& ls, int r0, int r1, int c0, int c1, Label l, int& valid)
{
	int hit = 0;
	valid = 0;
	for (int r = r0; r < r1; r++)
		for (int c = c0; c < c1; c++)
		{
			if (!ls.validMask.at<uint8_t>(r, c)) continue;
			valid++;
			hit += ls.label(r, c) == l;
		}
	return valid ? double(hit) / valid : 0.0;
}

class ThreeDtkPerception : public ::testing::TestWithParam<const char*>
{
};
}  // namespace

TEST_P(ThreeDtkPerception, FloorCeilingAndRightWall)
{
	SKIP_WITHOUT_3DTK(GetParam());
	const Sweep sw = ThreeDtkReader().read((kDataDir / GetParam()).string());
	PerceptionPipeline pipeline;
	const LabeledSweep ls = pipeline.process(sw);
	const int rows = ls.labels.rows, cols = ls.labels.cols, mid = cols / 2;
	int n = 0;

	// The arcade has a roof: indoor, floor below the scanner.
	EXPECT_TRUE(ls.indoor);
	EXPECT_TRUE(ls.groundEstimated);
	EXPECT_LT(ls.groundZ, -0.2);

	// Low rows around the centre column: the paved floor.
	const double floor =
	    fraction(ls, 0, 20, mid - 30, mid + 30, Label::Floor, n);
	EXPECT_GT(n, 500);
	EXPECT_GE(floor, 0.9) << "floor in the low rows ahead";

	// Top rows around the centre column: the roof.
	const double ceiling =
	    fraction(ls, rows - 12, rows, mid - 30, mid + 30, Label::Ceiling, n);
	EXPECT_GT(n, 300);
	EXPECT_GE(ceiling, 0.9) << "ceiling in the top rows ahead";

	// The solid wall on the right (phi -60..-30 deg), at mid height.
	const double wall =
	    fraction(ls, rows / 3, 2 * rows / 3, 60, 120, Label::Wall, n);
	EXPECT_GT(n, 1000);
	EXPECT_GE(wall, 0.8) << "right-hand wall";
	std::printf(
	    "%s: floor %.3f ceiling %.3f right wall %.3f\n", GetParam(), floor,
	    ceiling, wall);
}

INSTANTIATE_TEST_SUITE_P(
    Scans, ThreeDtkPerception, ::testing::Values("scan000.3d", "scan001.3d"));
