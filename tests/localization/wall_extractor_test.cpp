/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <semnav/common/Error.h>
#include <semnav/localization/WallExtractor.h>
#include <semnav/perception/LabeledSweep.h>

#include <random>

using namespace semnav;

namespace
{
/** A classified sweep with five regions of 20 x 40 pixels: wall along
 * y = 2 (x 1..4), wall along x = 5 (y -1..1.5), floor, a scattered "wall"
 * (not a plane) and a tilted "wall" (normal up). Noise 5 mm. */
LabeledSweep makeSweep()
{
	const int rows = 40, cols = 100;
	LabeledSweep ls;
	ls.labels = cv::Mat(rows, cols, CV_8U, cv::Scalar(0));
	ls.regionIds = cv::Mat(rows, cols, CV_32S, cv::Scalar(-1));
	ls.points = cv::Mat(rows, cols, CV_32FC3, cv::Scalar(0, 0, 0));
	std::mt19937 rng(3);
	std::normal_distribution<double> noise(0, 0.005), scatter(0, 0.3);
	const Label labels[] = {
	    Label::Wall, Label::Wall, Label::Floor, Label::Wall, Label::Wall};
	for (int k = 0; k < 5; k++)
	{
		LabeledRegion reg;
		reg.id = k;
		reg.label = labels[k];
		reg.pixels = 20 * rows;
		reg.imageBox = cv::Rect(20 * k, 0, 20, rows);
		reg.meanNormal = {0, 1, 0};
		if (k == 4) reg.meanNormal = {0, 0.4, 0.9};
		for (int r = 0; r < rows; r++)
			for (int c = 20 * k; c < 20 * k + 20; c++)
			{
				const double u = (c - 20 * k) / 19.0, v = r / 39.0;
				cv::Vec3f p;
				switch (k)
				{
					case 0:
						p = {
						    float(1 + 3 * u), float(2 + noise(rng)),
						    float(2 * v)};
						break;
					case 1:
						p = {
						    float(5 + noise(rng)), float(-1 + 2.5 * u),
						    float(2 * v)};
						break;
					case 2:
						p = {float(1 + 2 * u), float(-1 + 2 * v), 0.f};
						break;
					case 3:
						p = {
						    float(2 + scatter(rng)),
						    float(-2 + 2 * u + scatter(rng)), float(2 * v)};
						break;
					default:
						p = {float(3 + u), float(-3 + v), float(v)};
						break;
				}
				ls.points.at<cv::Vec3f>(r, c) = p;
				ls.regionIds.at<int>(r, c) = k;
				ls.labels.at<uint8_t>(r, c) = static_cast<uint8_t>(labels[k]);
			}
		ls.regions.push_back(reg);
	}
	return ls;
}
}  // namespace

TEST(WallExtractor, FitsPlanarVerticalWallsOnly)
{
	const auto obs = WallExtractor().extract(makeSweep());
	ASSERT_EQ(obs.segments.size(), 2u);
	const auto& a = obs.segments[0];
	EXPECT_NEAR(std::min(a.p0.x, a.p1.x), 1.0, 0.05);
	EXPECT_NEAR(std::max(a.p0.x, a.p1.x), 4.0, 0.05);
	EXPECT_NEAR(a.p0.y, 2.0, 0.01);
	EXPECT_NEAR(a.p1.y, 2.0, 0.01);
	EXPECT_NEAR(a.residual, 0.005, 0.002);
	EXPECT_GT(a.sigmaAngle, 0);
	EXPECT_LT(a.sigmaAngle, mrpt::DEG2RAD(0.1));
	EXPECT_LT(a.sigmaOffset, 0.001);
	const auto& b = obs.segments[1];
	EXPECT_NEAR(b.p0.x, 5.0, 0.01);
	EXPECT_NEAR(b.length(), 2.5, 0.08);
	// Samples lie on the segments, spaced as configured.
	ASSERT_FALSE(obs.samples.empty());
	EXPECT_NEAR(obs.samples.size(), (3.0 + 2.5) / 0.15, 2);
	for (const auto& s : obs.samples)
		EXPECT_TRUE(std::abs(s.y - 2) < 0.02 || std::abs(s.x - 5) < 0.02);
	// Two perpendicular walls: dominant direction 0 (mod 90).
	ASSERT_TRUE(obs.dominantDirection);
	EXPECT_NEAR(*obs.dominantDirection, 0.0, mrpt::DEG2RAD(0.2));
}

TEST(WallExtractor, SampleCountIsCapped)
{
	WallExtractor::TOptions o;
	o.maxSamples = 10;
	const auto obs = WallExtractor(o).extract(makeSweep());
	EXPECT_LE(obs.samples.size(), 10u);
	EXPECT_GE(obs.samples.size(), 9u);
}

TEST(WallExtractor, OptionsRejectUnknownKeysAndOutOfRangeValues)
{
	mrpt::config::CConfigFileMemory c;
	c.write("WallExtractor", "min_length_meters", 1.0);
	WallExtractor::TOptions o;
	EXPECT_THROW(o.loadFromConfigFile(c, "WallExtractor"), ConfigError);
	mrpt::config::CConfigFileMemory d;
	d.write("WallExtractor", "endpoint_quantile", 0.6);
	EXPECT_THROW(o.loadFromConfigFile(d, "WallExtractor"), ConfigError);
	mrpt::config::CConfigFileMemory e;
	e.write("WallExtractor", "min_length_m", 0.9);
	o.loadFromConfigFile(e, "WallExtractor");
	EXPECT_DOUBLE_EQ(o.minLength, 0.9);
}
