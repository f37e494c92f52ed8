/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <semnav/common/Error.h>
#include <semnav/training/SampleGenerator.h>

#include <opencv2/imgproc.hpp>
#include <random>

using namespace semnav;

namespace
{
uint16_t code(Label l, int inst)
{
	return static_cast<uint16_t>(static_cast<int>(l) | (inst << 8));
}

/** A 120 x 200 "sweep": noisy background, and (if `withObject`) a bright
 * 16 x 24 washbasin-like object with its ground truth. */
TrainingSweep sweep(uint64_t seed, bool withObject)
{
	std::mt19937_64 g(seed);
	TrainingSweep t;
	t.image = cv::Mat(120, 200, CV_8U);
	for (int r = 0; r < t.image.rows; r++)
		for (int c = 0; c < t.image.cols; c++)
			t.image.at<uint8_t>(r, c) = static_cast<uint8_t>(80 + g() % 40);
	t.groundTruth = cv::Mat(120, 200, CV_16U, cv::Scalar(3));
	if (withObject)
	{
		const cv::Rect obj(90, 50, 16, 24);
		t.image(obj).setTo(cv::Scalar(230));
		t.image(cv::Rect(95, 50, 6, 24)).setTo(cv::Scalar(20));
		t.groundTruth(obj).setTo(code(Label::Washbasin, 2));
	}
	return t;
}

/** Two passes: objects up to 20 px upscaled by 2 in rows 40..90, larger
 * ones at scale 1 in the whole image. */
std::vector<DetectionPass> twoPasses()
{
	DetectionPass nearPass, farPass;
	nearPass.rowEnd = 120;
	nearPass.minSide = 20;
	farPass.upscale = 2;
	farPass.rowBegin = 40;
	farPass.rowEnd = 90;
	farPass.minSide = 10;
	farPass.maxSide = 20;
	return {nearPass, farPass};
}
}  // namespace

TEST(SampleGenerator, PositivesAndNegativesAsTheDetectorSeesThem)
{
	SampleGenerator::TOptions o;
	o.positives = 40;
	SampleGenerator gen(o);
	std::vector<TrainingSweep> sweeps{
	    sweep(1, true), sweep(2, false), sweep(3, false)};
	for (auto& s : sweeps) s.passes = twoPasses();
	const auto res = gen.generate(sweeps, Label::Washbasin, {20, 20}, 7);
	EXPECT_EQ(res.views, 1u);
	EXPECT_EQ(res.sweepsWithoutObject, 2u);
	ASSERT_EQ(res.positives.size(), 40u);
	for (const auto& p : res.positives)
	{
		ASSERT_EQ(p.size(), cv::Size(20, 20));
		ASSERT_EQ(p.type(), CV_8UC1);
		// The object (bright and dark parts) is in the window.
		double mn, mx;
		cv::minMaxLoc(p, &mn, &mx);
		EXPECT_GT(mx, 150);
	}
	// Negatives: each pass of each sweep, object box excluded in pass
	// coordinates, pyramid scales of the pass.
	ASSERT_EQ(res.negatives.size(), 6u);
	const auto& n0 = res.negatives[0];
	EXPECT_EQ(n0.image.size(), cv::Size(200, 120));
	ASSERT_EQ(n0.exclude.size(), 1u);
	EXPECT_EQ(n0.exclude[0], cv::Rect(90, 50, 16, 24));
	EXPECT_DOUBLE_EQ(n0.minScale, 1.0);
	EXPECT_DOUBLE_EQ(n0.maxScale, 0.0);
	const auto& n1 = res.negatives[1];
	EXPECT_EQ(n1.image.size(), cv::Size(400, 100));
	EXPECT_EQ(n1.exclude[0], cv::Rect(180, 20, 32, 48));
	EXPECT_DOUBLE_EQ(n1.maxScale, 2.0);
	EXPECT_TRUE(res.negatives[2].exclude.empty());
	// Same seed, same samples; another seed, others.
	const auto again = gen.generate(sweeps, Label::Washbasin, {20, 20}, 7);
	const auto other = gen.generate(sweeps, Label::Washbasin, {20, 20}, 8);
	std::size_t same = 0, differ = 0;
	for (std::size_t i = 0; i < 40; i++)
	{
		same +=
		    cv::norm(res.positives[i], again.positives[i], cv::NORM_INF) == 0;
		differ +=
		    cv::norm(res.positives[i], other.positives[i], cv::NORM_INF) > 0;
	}
	EXPECT_EQ(same, 40u);
	EXPECT_GT(differ, 30u);
}

TEST(SampleGenerator, WarpKeepsAnUnrotatedObjectInPlace)
{
	SampleGenerator::TOptions o;
	o.margin = 0.0;
	SampleGenerator gen(o);
	const TrainingSweep s = sweep(1, true);
	const cv::Mat mask = s.groundTruth == code(Label::Washbasin, 2);
	// No rotation, no intensity change, own surroundings, side 24, scaled to
	// 24 x 24: the crop of the image around the object.
	const cv::Mat p = gen.makePositive(
	    s.image, mask, {90, 50, 16, 24}, {0, 0, 0}, 0, cv::Mat(), {24, 24},
	    1.0);
	cv::Mat ref;
	cv::getRectSubPix(s.image, {24, 24}, {98.f, 62.f}, ref);
	EXPECT_LE(cv::norm(p, ref, cv::NORM_INF), 1.0);
	// A random background replaces the surroundings, not the object.
	const cv::Mat bg(40, 40, CV_8U, cv::Scalar(0));
	const cv::Mat q = gen.makePositive(
	    s.image, mask, {90, 50, 16, 24}, {0, 0, 0}, 0, bg, {24, 24}, 1.0);
	EXPECT_EQ(q.at<uint8_t>(12, 0), 0);    // left of the object: background
	EXPECT_EQ(q.at<uint8_t>(12, 12), 20);  // the object's dark stripe
	// Intensity change applies to the object only.
	const cv::Mat r = gen.makePositive(
	    s.image, mask, {90, 50, 16, 24}, {0, 0, 0}, 10, bg, {24, 24}, 1.0);
	EXPECT_EQ(r.at<uint8_t>(12, 12), 30);
	EXPECT_EQ(r.at<uint8_t>(12, 0), 0);
}

TEST(SampleGenerator, RangeNegativesCarryTheRangeAndGateOfEachPass)
{
	SampleGenerator::TOptions o;
	o.positives = 4;
	std::vector<TrainingSweep> sweeps{sweep(1, true), sweep(2, false)};
	for (auto& s : sweeps)
	{
		s.passes = twoPasses();
		s.range = cv::Mat(120, 200, CV_32F, cv::Scalar(0));
		s.range.rowRange(60, 120).setTo(cv::Scalar(3.0));
		s.gate.perSide = 10;
		s.gate.hi = 1.5;
	}
	// Off: every window is a negative.
	for (const auto& n : SampleGenerator(o)
	                         .generate(sweeps, Label::Washbasin, {20, 20}, 7)
	                         .negatives)
		EXPECT_TRUE(n.range.empty());
	o.rangeNegatives = true;
	const auto res =
	    SampleGenerator(o).generate(sweeps, Label::Washbasin, {20, 20}, 7);
	ASSERT_EQ(res.negatives.size(), 4u);
	for (const auto& n : res.negatives)
	{
		ASSERT_EQ(n.range.size(), n.image.size());
		EXPECT_EQ(n.range.type(), CV_32F);
		EXPECT_DOUBLE_EQ(n.gate.hi, 1.5);
	}
	// The far pass: rows 40..90 upscaled by 2 (range from row 60 on, i.e.
	// band row 20, upscaled row 40), gate per upscaled pixel.
	const auto& far = res.negatives[1];
	EXPECT_DOUBLE_EQ(far.gate.perSide, 20.0);
	EXPECT_EQ(far.range.at<float>(39, 10), 0.0f);
	EXPECT_EQ(far.range.at<float>(40, 10), 3.0f);
	EXPECT_DOUBLE_EQ(res.negatives[0].gate.perSide, 10.0);
}

TEST(SampleGenerator, ErrorsAndOptions)
{
	SampleGenerator gen;
	EXPECT_THROW(
	    gen.generate({sweep(2, false)}, Label::Washbasin, {20, 20}, 1), Error);
	SampleGenerator::TOptions o;
	mrpt::config::CConfigFileMemory c(
	    "[S]\npositives = 12\nmax_z_angle_deg = 30\n");
	o.loadFromConfigFile(c, "S");
	EXPECT_EQ(o.positives, 12);
	EXPECT_NEAR(o.maxAngleZ, 30 * M_PI / 180, 1e-12);
	mrpt::config::CConfigFileMemory rn("[S]\nrange_negatives = true\n");
	o.loadFromConfigFile(rn, "S");
	EXPECT_TRUE(o.rangeNegatives);
	mrpt::config::CConfigFileMemory bad("[S]\npositive = 12\n");
	EXPECT_THROW(o.loadFromConfigFile(bad, "S"), ConfigError);
	mrpt::config::CConfigFileMemory range("[S]\njitter = 0.9\n");
	EXPECT_THROW(o.loadFromConfigFile(range, "S"), ConfigError);
}
