/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <semnav/common/Error.h>
#include <semnav/perception/GroundTruthScorer.h>
#include <unistd.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>

using namespace semnav;

TEST(GroundTruthScorer, PrecisionRecallF1OverValidPixels)
{
	// 1 x 6: gt     F F F W W W
	//        pred   F F W W W F
	//        valid  1 1 1 1 1 0
	cv::Mat gt = (cv::Mat_<uint8_t>(1, 6) << 1, 1, 1, 3, 3, 3);
	cv::Mat pred = (cv::Mat_<uint8_t>(1, 6) << 1, 1, 3, 3, 3, 1);
	cv::Mat valid = (cv::Mat_<uint8_t>(1, 6) << 1, 1, 1, 1, 1, 0);
	GroundTruthScorer s;
	s.add(pred, gt, valid);
	const auto floor = s.score(Label::Floor);
	EXPECT_EQ(floor.truePositives, 2u);
	EXPECT_EQ(floor.falseNegatives, 1u);
	EXPECT_EQ(floor.falsePositives, 0u);  // the 6th pixel is not scored
	EXPECT_DOUBLE_EQ(floor.precision, 1.0);
	EXPECT_DOUBLE_EQ(floor.recall, 2.0 / 3.0);
	EXPECT_DOUBLE_EQ(floor.f1, 0.8);
	const auto wall = s.score(Label::Wall);
	EXPECT_DOUBLE_EQ(wall.precision, 2.0 / 3.0);
	EXPECT_DOUBLE_EQ(wall.recall, 1.0);
	EXPECT_EQ(wall.groundTruthPixels, 2u);
	EXPECT_EQ(s.scoredPixels(), 5u);
	EXPECT_EQ(s.confusion(Label::Floor, Label::Wall), 1u);
	EXPECT_EQ(s.labelsSeen(), (std::vector<Label>{Label::Floor, Label::Wall}));
	const auto door = s.score(Label::Door);
	EXPECT_EQ(door.f1, 0.0);

	// Accumulates over sweeps; 16-bit ground truth uses its low byte.
	cv::Mat gt16(1, 6, CV_16U);
	for (int c = 0; c < 6; c++)
		gt16.at<uint16_t>(0, c) =
		    static_cast<uint16_t>(gt.at<uint8_t>(0, c) | (7 << 8));
	s.add(pred, gt16, valid);
	EXPECT_EQ(s.sweeps(), 2u);
	EXPECT_EQ(s.score(Label::Floor).truePositives, 4u);
	EXPECT_DOUBLE_EQ(s.score(Label::Floor).f1, 0.8);
}

TEST(GroundTruthScorer, RejectsMismatchesAndReadsPngs)
{
	GroundTruthScorer s;
	cv::Mat a(2, 3, CV_8U, cv::Scalar(1)), b(3, 2, CV_8U, cv::Scalar(1));
	EXPECT_THROW(s.add(a, b, a), Error);
	cv::Mat bad(2, 3, CV_8U, cv::Scalar(40));
	EXPECT_THROW(s.add(a, bad, a), Error);

	const auto dir = std::filesystem::temp_directory_path() /
	                 ("semnav_gt_" + std::to_string(::getpid()));
	std::filesystem::create_directories(dir);
	cv::Mat gt16(2, 2, CV_16U);
	gt16.at<uint16_t>(0, 0) = 1 | (5 << 8);
	gt16.at<uint16_t>(0, 1) = 3;
	gt16.at<uint16_t>(1, 0) = 4 | (2 << 8);
	gt16.at<uint16_t>(1, 1) = 0;
	ASSERT_TRUE(cv::imwrite((dir / "gt.png").string(), gt16));
	const cv::Mat l =
	    GroundTruthScorer::readLabelImage((dir / "gt.png").string());
	ASSERT_EQ(l.type(), CV_8U);
	EXPECT_EQ(l.at<uint8_t>(0, 0), 1);
	EXPECT_EQ(l.at<uint8_t>(0, 1), 3);
	EXPECT_EQ(l.at<uint8_t>(1, 0), 4);
	EXPECT_THROW(
	    GroundTruthScorer::readLabelImage((dir / "none.png").string()),
	    IoError);
	cv::Mat wrong(2, 2, CV_16U, cv::Scalar(60));
	ASSERT_TRUE(cv::imwrite((dir / "wrong.png").string(), wrong));
	EXPECT_THROW(
	    GroundTruthScorer::readLabelImage((dir / "wrong.png").string()),
	    IoError);
	std::filesystem::remove_all(dir);
}
