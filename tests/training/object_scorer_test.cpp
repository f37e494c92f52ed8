/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <semnav/training/GroundTruthObject.h>
#include <semnav/training/ObjectScorer.h>

#include <opencv2/core.hpp>

using namespace semnav;

namespace
{
uint16_t labelCode(Label l, int inst)
{
	return static_cast<uint16_t>(static_cast<int>(l) | (inst << 8));
}
Detection det(Label l, cv::Rect box, double score = 1)
{
	Detection d;
	d.label = l;
	d.imageBox = box;
	d.score = score;
	return d;
}
}  // namespace

TEST(GroundTruthObject, InstancesWithBoxesAndPixels)
{
	cv::Mat gt(50, 80, CV_16U, cv::Scalar(static_cast<int>(Label::Wall)));
	gt(cv::Rect(10, 10, 12, 15)).setTo(labelCode(Label::Washbasin, 4));
	gt(cv::Rect(40, 5, 5, 5)).setTo(labelCode(Label::Wastebasket, 9));
	gt(cv::Rect(60, 30, 10, 10))
	    .setTo(labelCode(Label::Washbasin, 0));  // no id
	const auto objs = GroundTruthObject::fromLabelImage(
	    gt, {Label::Washbasin, Label::Wastebasket});
	ASSERT_EQ(objs.size(), 2u);
	EXPECT_EQ(objs[0].label, Label::Washbasin);
	EXPECT_EQ(objs[0].instance, 4);
	EXPECT_EQ(objs[0].box, cv::Rect(10, 10, 12, 15));
	EXPECT_EQ(objs[0].pixels, 180);
	EXPECT_EQ(cv::countNonZero(objs[0].mask(gt)), 180);
	EXPECT_EQ(objs[1].label, Label::Wastebasket);
	// The share of some pixels on the washbasin: 3 of 4 (one on the wall),
	// none of the wastebasket's, and none of nothing.
	const std::vector<cv::Point> px{{10, 10}, {21, 24}, {15, 12}, {0, 0}};
	EXPECT_DOUBLE_EQ(objs[0].shareOf(gt, px), 0.75);
	EXPECT_DOUBLE_EQ(objs[1].shareOf(gt, px), 0.0);
	EXPECT_DOUBLE_EQ(objs[0].shareOf(gt, {}), 0.0);
}

TEST(ObjectScorer, IssueRules)
{
	// Washbasin 1: 20 x 10 = 200 px (counts); washbasin 2: 10 x 10 = 100 px
	// (too small to count); wastebasket: 15 x 12 = 180 px (counts).
	cv::Mat gt(100, 100, CV_16U, cv::Scalar(0));
	gt(cv::Rect(10, 10, 20, 10)).setTo(labelCode(Label::Washbasin, 1));
	gt(cv::Rect(60, 60, 10, 10)).setTo(labelCode(Label::Washbasin, 2));
	gt(cv::Rect(40, 70, 15, 12)).setTo(labelCode(Label::Wastebasket, 3));
	const std::vector<Label> labels{Label::Washbasin, Label::Wastebasket};
	ObjectScorer s;
	s.add(
	    {det(Label::Washbasin, {10, 10, 20, 12}, 5),  // tp (IoU 0.83)
	     det(Label::Washbasin, {12, 11, 18, 10}, 2),  // duplicate: fp
	     det(Label::Washbasin, {60, 60, 11, 11}),     // small object: ignored
	     det(Label::Washbasin, {80, 5, 10, 10}),      // nothing there: fp
	     det(Label::Wastebasket, {10, 10, 20, 10})},  // wrong label: fp
	    gt, labels);
	const auto w = s.score(Label::Washbasin);
	EXPECT_EQ(w.tp, 1u);
	EXPECT_EQ(w.fp, 2u);
	EXPECT_EQ(w.fn, 0u);
	EXPECT_EQ(w.ignored, 1u);
	EXPECT_DOUBLE_EQ(w.precision, 1.0 / 3.0);
	EXPECT_DOUBLE_EQ(w.recall, 1.0);
	const auto b = s.score(Label::Wastebasket);
	EXPECT_EQ(b.tp, 0u);
	EXPECT_EQ(b.fp, 1u);
	EXPECT_EQ(b.fn, 1u);
	EXPECT_DOUBLE_EQ(b.recall, 0.0);
	// IoU threshold 0.3 is inclusive, and boxes are matched once.
	EXPECT_NEAR(
	    ObjectScorer::iou({0, 0, 10, 10}, {0, 0, 10, 30}), 1.0 / 3, 1e-12);
	ObjectScorer t;
	t.add({det(Label::Washbasin, {10, 10, 20, 30})}, gt, labels);  // IoU 1/3
	EXPECT_EQ(t.score(Label::Washbasin).tp, 1u);
	EXPECT_EQ(t.sweeps(), 1u);
}

TEST(ObjectScorer, ExcludedObjectsAreNotScored)
{
	cv::Mat gt(100, 100, CV_16U, cv::Scalar(0));
	gt(cv::Rect(10, 10, 20, 10)).setTo(labelCode(Label::Washbasin, 1));
	gt(cv::Rect(50, 50, 20, 10)).setTo(labelCode(Label::Washbasin, 2));
	gt(cv::Rect(10, 70, 20, 10)).setTo(labelCode(Label::Washbasin, 3));
	const std::vector<Label> labels{Label::Washbasin};
	ObjectScorer s;
	s.add(
	    {det(Label::Washbasin, {10, 10, 20, 10}),   // tp
	     det(Label::Washbasin, {50, 50, 20, 10})},  // of an excluded one
	    gt, labels, {{Label::Washbasin, 2}, {Label::Washbasin, 3}});
	const auto w = s.score(Label::Washbasin);
	EXPECT_EQ(w.tp, 1u);
	EXPECT_EQ(w.fp, 0u);
	EXPECT_EQ(w.fn, 0u);  // washbasin 3 is excluded, not missed
	EXPECT_EQ(w.ignored, 1u);
}

TEST(ObjectScorer, ObjectsOfFewDistinctPointsAreFound)
{
	// Two 20 x 10 washbasins: one over 200 points 5 cm apart, one whose
	// pixels repeat four points (as beside the robot).
	cv::Mat gt(100, 100, CV_16U, cv::Scalar(0));
	cv::Mat points(100, 100, CV_32FC3, cv::Scalar::all(NAN));
	const cv::Rect spread(10, 10, 20, 10), repeated(50, 50, 20, 10);
	gt(spread).setTo(labelCode(Label::Washbasin, 1));
	gt(repeated).setTo(labelCode(Label::Washbasin, 2));
	for (int r = 0; r < 10; r++)
		for (int c = 0; c < 20; c++)
		{
			points.at<cv::Vec3f>(spread.y + r, spread.x + c) =
			    cv::Vec3f(2.0f, 0.05f * float(c), 0.05f * float(r));
			points.at<cv::Vec3f>(repeated.y + r, repeated.x + c) =
			    cv::Vec3f(3.0f, 0.05f * float(c % 2), 0.05f * float(r % 2));
		}
	EXPECT_EQ(
	    ObjectScorer::distinctCells(
	        gt == labelCode(Label::Washbasin, 1), points, 0.02),
	    200u);
	EXPECT_EQ(
	    ObjectScorer::distinctCells(
	        gt == labelCode(Label::Washbasin, 2), points, 0.02),
	    4u);
	// At 10 cm cells the spread one fills 50 cells.
	EXPECT_EQ(
	    ObjectScorer::distinctCells(
	        gt == labelCode(Label::Washbasin, 1), points, 0.1),
	    50u);
	const ObjectScorer s;
	const auto few = s.fewDistinctPoints(gt, points, {Label::Washbasin});
	EXPECT_EQ(few, (ObjectScorer::ObjectKeys{{Label::Washbasin, 2}}));
}
