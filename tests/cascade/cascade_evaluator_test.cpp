/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <semnav/cascade/CascadeEvaluator.h>
#include <semnav/cascade/CascadeTrainer.h>
#include <semnav/cascade/CascadeXml.h>

#include <filesystem>
#include <map>
#include <opencv2/imgproc.hpp>
#include <opencv2/objdetect.hpp>

#include "CascadeTestUtils.h"

using namespace semnav;

namespace
{
struct Key
{
	int x, y;
	bool operator<(const Key& o) const { return y != o.y ? y < o.y : x < o.x; }
};

/** Loads `cascade` into cv::CascadeClassifier through the XML text. */
cv::CascadeClassifier toOpenCv(const HaarCascade& cascade)
{
	const std::string xml = CascadeXml::toString(cascade);
	cv::FileStorage fs(xml, cv::FileStorage::READ | cv::FileStorage::MEMORY);
	cv::CascadeClassifier cc;
	EXPECT_TRUE(cc.read(fs.getFirstTopLevelNode()));
	return cc;
}

/** Windows accepted at scale 1 by cv::CascadeClassifier and by
 * CascadeEvaluator must be the same, with bit-identical last-stage sums
 * (OpenCV's levelWeights). Returns the number accepted. */
std::size_t expectSameAccepted(const HaarCascade& cascade, const cv::Mat& img)
{
	cv::CascadeClassifier cc = toOpenCv(cascade);
	const cv::Size win = cascade.windowSize;
	const bool oneStage = cascade.stages.size() == 1;
	// minNeighbors 0: no grouping; min = max size: scale 1 only.
	std::vector<cv::Rect> plain;
	cc.detectMultiScale(img, plain, 1.1, 0, 0, win, win);
	// With outputRejectLevels OpenCV 4.6 reports the windows whose result
	// r satisfies stages + r == 0 (CascadeClassifierInvoker): accepted ones
	// (r = 1 -> -stages) with the last stage's sum, and, for a one-stage
	// cascade, also those skipped by the variance test (r = -1; their
	// weight is stale).
	std::vector<cv::Rect> found;
	std::vector<int> levels;
	std::vector<double> weights;
	cc.detectMultiScale(img, found, levels, weights, 1.1, 0, 0, win, win, true);

	std::map<Key, double> cvWeight;
	for (std::size_t i = 0; i < found.size(); i++)
	{
		EXPECT_EQ(found[i].size(), win);
		cvWeight[{found[i].x, found[i].y}] = weights[i];
	}
	std::map<Key, bool> cvPlain;
	for (const auto& r : plain) cvPlain[{r.x, r.y}] = true;

	CascadeEvaluator ev(cascade);
	ev.setImage(img);
	std::size_t accepted = 0, reported = 0;
	for (const auto& w : ev.scanScaleOne())
	{
		const Key key{w.origin.x, w.origin.y};
		const bool acc = ev.accepted(w.result);
		EXPECT_EQ(acc, cvPlain.count(key) == 1)
		    << "accepted by " << (acc ? "semnav only" : "OpenCV only") << " at "
		    << w.origin << " (" << cascade.stages.size() << " stages)";
		const bool expectReported = acc || (oneStage && w.result.skipped());
		EXPECT_EQ(expectReported, cvWeight.count(key) == 1)
		    << "at " << w.origin << ", semnav stage " << w.result.stage << " ("
		    << cascade.stages.size() << " stages)";
		if (acc && cvWeight.count(key))
			EXPECT_EQ(w.result.sum, cvWeight[key]) << "at " << w.origin;
		accepted += acc;
		reported += expectReported;
	}
	EXPECT_EQ(accepted, plain.size())
	    << "windows accepted (" << cascade.stages.size() << " stages)";
	EXPECT_EQ(reported, found.size());
	return accepted;
}

/** Window by window: for every k, the windows that pass the first k stages
 * (and their stage-k sums) are the same in both, so every window is
 * rejected by the same stage with the same sums; the scan order with
 * OpenCV's skip after a stage-0 rejection is covered by k = 1. Returns the
 * number of windows the whole cascade accepts. */
std::size_t expectAgreement(const HaarCascade& cascade, const cv::Mat& img)
{
	std::size_t accepted = 0, passedFirst = 0;
	for (std::size_t k = 1; k <= cascade.stages.size(); k++)
	{
		const std::size_t n = expectSameAccepted(cascade.firstStages(k), img);
		if (k == 1) passedFirst = n;
		accepted = n;
	}
	EXPECT_GT(passedFirst, 0u) << "weak test: no window passes stage 0";
	return accepted;
}

/** Test scene: clutter with smoothed edges and a few synthetic objects. */
cv::Mat testImage(cv::Size sz, cv::Size win, uint64_t seed)
{
	std::mt19937_64 g(seed);
	cv::Mat img = test::syntheticBackground(sz, g);
	cv::GaussianBlur(img, img, {3, 3}, 0.8);
	for (int i = 0; i < 6; i++)
	{
		const cv::Mat obj = test::syntheticPositive(win, g);
		const cv::Point at(
		    int(g() % (sz.width - win.width)),
		    int(g() % (sz.height - win.height)));
		obj.copyTo(img(cv::Rect(at, win)));
	}
	return img;
}

const HaarCascade& trainedCascade()
{
	static const HaarCascade c = []
	{
		std::vector<cv::Mat> pos;
		std::vector<NegativeImage> neg;
		test::syntheticTrainingSet({20, 20}, 120, pos, neg);
		auto o = test::tinyTrainerOptions({20, 20});
		o.featureFraction = 0.1;
		CascadeTrainer t(o);
		return t.train(pos, neg, 3);
	}();
	return c;
}
}  // namespace

TEST(CascadeEvaluator, AgreesWithOpenCvOnOwnTrainedCascade)
{
	const HaarCascade& c = trainedCascade();
	ASSERT_GE(c.stages.size(), 2u);
	std::size_t accepted = 0;
	for (uint64_t seed : {1, 2})
	{
		const cv::Mat img = testImage({161, 122}, c.windowSize, seed);
		accepted += expectAgreement(c, img);
		// Odd offsets: OpenCV visits even positions only.
		expectAgreement(c, img(cv::Rect(1, 1, 150, 111)).clone());
	}
	EXPECT_GT(accepted, 0u) << "no window accepted: weak test";
}

TEST(CascadeEvaluator, AgreesWithOpenCvOnShippedFaceCascade)
{
	const std::string path =
	    test::openCvCascade("haarcascade_frontalface_default.xml");
	if (path.empty())
		GTEST_SKIP() << "opencv-data is not installed "
		                "(haarcascade_frontalface_default.xml missing)";
	const HaarCascade face = CascadeXml::readFile(path);
	const cv::Mat img = testImage({200, 150}, {24, 24}, 5);
	expectAgreement(face, img);
}

/** OpenCV's shipped cascade with 45-degree features (opencv-data). */
class TiltedCascade : public ::testing::Test
{
protected:
	void SetUp() override
	{
		const std::string path =
		    test::openCvCascade("haarcascade_frontalcatface_extended.xml");
		if (path.empty())
			GTEST_SKIP() << "opencv-data is not installed "
			                "(haarcascade_frontalcatface_extended.xml missing)";
		cat = CascadeXml::readFile(path);
		ASSERT_TRUE(cat.hasTiltedFeatures());
	}
	HaarCascade cat;
};

TEST_F(TiltedCascade, EvaluatorAgreesWithOpenCv)
{
	const cv::Mat img = testImage({180, 140}, cat.windowSize, 8);
	expectAgreement(cat, img);
}

TEST(CascadeEvaluator, SkipsLowContrastWindowsAsOpenCv)
{
	const HaarCascade& c = trainedCascade();
	CascadeEvaluator ev(c);
	// Standard deviation 10 exactly (alternating 110 / 130): skipped.
	cv::Mat flat(c.windowSize, CV_8UC1);
	for (int y = 0; y < flat.rows; y++)
		for (int x = 0; x < flat.cols; x++)
			flat.at<uint8_t>(y, x) = (x + y) % 2 ? 130 : 110;
	ev.setImage(flat);
	EXPECT_TRUE(ev.evaluate({0, 0}).skipped());
	cv::Mat contrast = flat.clone();
	for (int y = 0; y < flat.rows; y++)
		for (int x = 0; x < flat.cols; x++)
			contrast.at<uint8_t>(y, x) = (x + y) % 2 ? 140 : 100;
	ev.setImage(contrast);
	EXPECT_FALSE(ev.evaluate({0, 0}).skipped());
	EXPECT_TRUE(ev.evaluate({1, 0}).skipped()) << "window leaves the image";
}

namespace
{
/** scanWindows() against evaluate() window by window, with OpenCV's skip
 * after a stage-0 rejection done by hand: the windows of one level on its
 * grid (`step`), a pseudo-random third of them left out (the range gate),
 * SIMD on and off. Returns {accepted, not visited}. */
std::pair<std::size_t, std::size_t> expectScanIsEvaluate(
    const HaarCascade& cascade, const cv::Mat& img, int step, int stride)
{
	CascadeEvaluator ev(cascade);
	IntegralImages ii;
	if (stride > 0)
		ii.compute(img, cascade.hasTiltedFeatures(), stride);
	else
		ii.compute(img, cascade.hasTiltedFeatures());
	ev.setIntegralImages(ii);
	const cv::Size win = cascade.windowSize;
	std::vector<cv::Point> windows;
	std::mt19937 g(step + 10 * img.cols);
	// Windows outside the image (evaluate() skips them), one before a row
	// of windows on the grid and one after it.
	windows.emplace_back(-step, 0);
	for (int y = 0; y + win.height <= img.rows; y += step)
	{
		for (int x = 0; x + win.width <= img.cols; x += step)
			if (g() % 3 != 0) windows.emplace_back(x, y);
		if (y == 0) windows.emplace_back(img.cols - win.width + step, 0);
	}
	windows.emplace_back(img.cols, img.rows);
	std::vector<CascadeEvaluator::Result> expected;
	cv::Point skip(-1, -1);
	std::size_t accepted = 0, notVisited = 0;
	for (const cv::Point& w : windows)
	{
		CascadeEvaluator::Result r;
		if (w == skip)
		{
			r.stage = CascadeEvaluator::kNotVisited;
			notVisited++;
		}
		else
		{
			r = ev.evaluate(w);
			if (r.stage == 0) skip = cv::Point(w.x + step, w.y);
			accepted += ev.accepted(r);
		}
		expected.push_back(r);
	}
	for (const bool simd : {true, false})
	{
		ev.setSimd(simd);
		std::vector<CascadeEvaluator::Result> got;
		ev.scanWindows(windows, step, got);
		if (!simd) EXPECT_FALSE(ev.simdActive());
		EXPECT_EQ(got.size(), expected.size());
		for (std::size_t i = 0; i < got.size() && i < expected.size(); i++)
		{
			EXPECT_EQ(got[i].stage, expected[i].stage)
			    << windows[i] << " step " << step << " simd " << simd;
			// Bit for bit (EXPECT_EQ on doubles, not EXPECT_DOUBLE_EQ).
			EXPECT_EQ(got[i].sum, expected[i].sum)
			    << windows[i] << " step " << step << " simd " << simd;
		}
	}
	return {accepted, notVisited};
}
}  // namespace

TEST(CascadeEvaluator, ScanWindowsIsEvaluateWithOpenCvsSkip)
{
	const HaarCascade& c = trainedCascade();
	std::size_t accepted = 0, notVisited = 0;
	for (uint64_t seed : {1, 2})
		for (int step : {1, 2})
			for (int stride : {0, 200})
			{
				const cv::Mat img = testImage({161, 122}, c.windowSize, seed);
				const auto [a, n] = expectScanIsEvaluate(c, img, step, stride);
				accepted += a;
				notVisited += n;
			}
	EXPECT_GT(accepted, 0u) << "weak test: no window accepted";
	EXPECT_GT(notVisited, 0u) << "weak test: no stage-0 skip";
	// Nothing to scan.
	CascadeEvaluator ev(c);
	ev.setImage(testImage({40, 40}, c.windowSize, 3));
	std::vector<CascadeEvaluator::Result> r(3);
	ev.scanWindows({}, 2, r);
	EXPECT_TRUE(r.empty());
}

TEST_F(TiltedCascade, ScanWindowsIsEvaluate)
{
	for (int step : {1, 2})
	{
		const cv::Mat img = testImage({180, 140}, cat.windowSize, 8);
		expectScanIsEvaluate(cat, img, step, 0);
		expectScanIsEvaluate(cat, img, step, 190);
	}
}
