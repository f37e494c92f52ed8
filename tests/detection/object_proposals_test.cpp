/* semnav: semantic navigation from tilting-laser sweeps */
// Object proposals (regions the rule classifier leaves to objects) and the
// search regions the cascade detector derives from them. The suite names
// start with "Detector" so that `ctest -R Detect` runs them.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <semnav/common/Error.h>
#include <semnav/detection/CascadeDetector.h>
#include <semnav/detection/ObjectProposals.h>

#include <cmath>
#include <limits>

#include "../common/SavedAndLoaded.h"

using namespace semnav;

namespace
{
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

/** A 60 x 100 sweep-layout patch (ground at z = 0), all ranges along x:
 * - floor (label floor, z = 0) everywhere not listed below;
 * - a wall (label wall) 5 m ahead in cols [70, 100), z 0 .. 2.9;
 * - a wastebasket-like object 2 m ahead in cols [10, 20), rows [0, 20),
 *   z 0.02 .. 0.40 (label obstacle);
 * - the broad side of a near object labelled "wall" by the rules: cols
 *   [30, 40), rows [0, 25), 1.5 m ahead, z 0.02 .. 0.50 (its area is low);
 * - a table: legs at cols [45, 47) and [57, 59) (rows [0, 36), z up to
 *   0.72) joined by a top (rows [36, 40), cols [45, 59), z 0.72 .. 0.75),
 *   3 m ahead (label obstacle);
 * - an object 4 m ahead right beside the wastebasket in cols [20, 26),
 *   same rows and heights (label obstacle): another range.
 * `areas` holds one segmentation area per surface. */
struct Patch
{
	cv::Mat points, labels, areas;
};

Patch patch()
{
	Patch p;
	p.points = cv::Mat(60, 100, CV_32FC3);
	p.labels = cv::Mat(60, 100, CV_8U, cv::Scalar(int(Label::Floor)));
	p.areas = cv::Mat(60, 100, CV_32S, cv::Scalar(1));
	for (int r = 0; r < 60; r++)
		for (int c = 0; c < 100; c++)
		{
			const float y = 0.01f * float(50 - c);
			auto& pt = p.points.at<cv::Vec3f>(r, c);
			pt = {6.0f, y, 0.0f};  // floor
			const auto set = [&](float x, float z, Label l, int area)
			{
				pt = {x, y, z};
				p.labels.at<uint8_t>(r, c) = static_cast<uint8_t>(l);
				p.areas.at<int>(r, c) = area;
			};
			if (c >= 70)
				set(5.0f, 0.05f * float(r), Label::Wall, 2);
			else if (c >= 10 && c < 20 && r < 20)
				set(2.0f, 0.02f + 0.02f * float(r), Label::Obstacle, 3);
			else if (c >= 20 && c < 26 && r < 20)
				set(4.0f, 0.02f + 0.02f * float(r), Label::Obstacle, 4);
			else if (c >= 30 && c < 40 && r < 25)
				set(1.5f, 0.02f + 0.02f * float(r), Label::Wall, 5);
			else if (((c >= 45 && c < 47) || (c >= 57 && c < 59)) && r < 36)
				set(3.0f, 0.02f * float(r + 1), Label::Obstacle, 6);
			else if (c >= 45 && c < 59 && r >= 36 && r < 40)
				set(3.0f, 0.72f + 0.01f * float(r - 36), Label::Obstacle, 6);
			else if (r >= 55)
				pt = {kNaN, kNaN, kNaN};  // no return
		}
	return p;
}

ObjectProposals::Params params()
{
	ObjectProposals::Params pp;
	pp.minPixels = 10;
	pp.joinRadius = 1;
	pp.rangeGap = 0.3;
	return pp;
}

const ObjectProposal* at(
    const std::vector<ObjectProposal>& ps, cv::Point inside)
{
	for (const auto& p : ps)
		if (p.box.contains(inside)) return &p;
	return nullptr;
}
}  // namespace

TEST(DetectorProposals, MaskKeepsObjectsAndLowWallAreasOnly)
{
	const Patch p = patch();
	const cv::Mat m =
	    ObjectProposals::objectMask(p.points, p.labels, p.areas, 0.0, params());
	EXPECT_EQ(m.at<uint8_t>(5, 15), 1);  // object
	EXPECT_EQ(m.at<uint8_t>(5, 35), 1);  // low "wall" area: an object side
	EXPECT_EQ(m.at<uint8_t>(5, 80), 0);  // the wall reaches 2.9 m
	EXPECT_EQ(m.at<uint8_t>(30, 5), 0);  // floor
	EXPECT_EQ(m.at<uint8_t>(57, 5), 0);  // no return
	EXPECT_EQ(m.at<uint8_t>(0, 15), 0);  // 2 cm: within the floor tolerance
	// Without areas, same-label pixels form the surfaces: the low "wall"
	// touches no other wall pixel, so it stays an object too.
	const cv::Mat m2 = ObjectProposals::objectMask(
	    p.points, p.labels, cv::Mat(), 0.0, params());
	EXPECT_EQ(m2.at<uint8_t>(5, 35), 1);
	EXPECT_EQ(m2.at<uint8_t>(5, 80), 0);
	// A lower cap turns the same area into a surface.
	auto low = params();
	low.maxHeight = 0.3;
	const cv::Mat m3 =
	    ObjectProposals::objectMask(p.points, p.labels, p.areas, 0.0, low);
	EXPECT_EQ(m3.at<uint8_t>(5, 35), 0);
	EXPECT_THROW(
	    ObjectProposals::objectMask(
	        p.points, cv::Mat(3, 3, CV_8U), p.areas, 0.0, params()),
	    Error);
}

TEST(DetectorProposals, RegionsSplitByRangeAndHeightLimit)
{
	const Patch p = patch();
	const auto sets = ObjectProposals::find(
	    p.points, p.labels, p.areas, 0.0, nullptr, {0.65, 2.0}, params());
	ASSERT_EQ(sets.size(), 2u);
	for (const auto& ps : sets)
	{
		// The object 2 m ahead and its neighbour 4 m ahead are apart.
		const ObjectProposal* a = at(ps, {15, 10});
		const ObjectProposal* b = at(ps, {23, 10});
		ASSERT_TRUE(a && b);
		EXPECT_NE(a, b);
		EXPECT_EQ(a->box, cv::Rect(10, 1, 10, 19));
		// Horizontal ranges hypot(2, 0.31 .. 0.40): 10th and 90th
		// percentile.
		EXPECT_NEAR(a->nearRange, 2.025, 0.004);
		EXPECT_NEAR(a->farRange, 2.038, 0.004);
		EXPECT_NEAR(a->bottom, 0.04, 0.011);
		EXPECT_NEAR(a->top, 0.38, 0.021);
		EXPECT_NEAR(b->nearRange, std::hypot(4.0, 0.26), 0.03);
		// Nothing of the wall or the floor.
		EXPECT_EQ(at(ps, {80, 10}), nullptr);
		EXPECT_EQ(at(ps, {5, 45}), nullptr);
	}
	// Below 0.65 m the table is two legs; with its top, one region.
	const auto& low = sets[0];
	const auto& all = sets[1];
	ASSERT_TRUE(at(low, {45, 5}) && at(low, {58, 5}));
	EXPECT_NE(at(low, {45, 5}), at(low, {58, 5}));
	ASSERT_TRUE(at(all, {45, 5}));
	EXPECT_EQ(at(all, {45, 5}), at(all, {58, 5}));
	EXPECT_EQ(at(all, {45, 5})->box, cv::Rect(45, 1, 14, 39));
	// The legs below 0.65 m are the feet of something taller (the top joins
	// them); the objects are whole.
	EXPECT_GT(at(low, {45, 5})->tallerPixels, 0);
	EXPECT_GT(at(low, {58, 5})->tallerPixels, 0);
	EXPECT_EQ(at(low, {15, 10})->tallerPixels, 0);
	EXPECT_EQ(at(all, {45, 5})->tallerPixels, 0);
	// Over a mask computed before: the same regions; a pixel the mask
	// leaves out is in none.
	cv::Mat mask =
	    ObjectProposals::objectMask(p.points, p.labels, p.areas, 0.0, params());
	const auto again = ObjectProposals::findInMask(
	    p.points, mask, 0.0, nullptr, {2.0}, params());
	ASSERT_EQ(again.size(), 1u);
	ASSERT_EQ(again[0].size(), all.size());
	for (std::size_t i = 0; i < all.size(); i++)
		EXPECT_EQ(again[0][i].box, all[i].box);
	mask(cv::Rect(10, 0, 10, 20)).setTo(0);
	const auto without = ObjectProposals::findInMask(
	    p.points, mask, 0.0, nullptr, {2.0}, params());
	EXPECT_EQ(at(without[0], {15, 10}), nullptr);
	EXPECT_NE(at(without[0], {23, 10}), nullptr);
	EXPECT_THROW(
	    ObjectProposals::findInMask(
	        p.points, cv::Mat(3, 3, CV_8U), 0.0, nullptr, {2.0}, params()),
	    Error);
	// Small regions are dropped.
	auto big = params();
	big.minPixels = 500;
	const auto none = ObjectProposals::find(
	    p.points, p.labels, p.areas, 0.0, nullptr, {2.0}, big);
	EXPECT_TRUE(none[0].empty());
}

TEST(DetectorProposals, SearchRegionsFitTheRangeAndTheRegion)
{
	CascadeDetector::TOptions o;
	o.classes.clear();
	o.proposalSizeSlack = 1.15;
	o.proposalFill = 0.5;
	o.proposalMargin = 0.5;
	// A detector without classes loads no cascade; searchRegions only
	// reads the options.
	CascadeDetector det(o);
	CascadeDetector::TClassOptions k(Label::Wastebasket);
	k.minSize = 0.3;
	k.minCutSize = 0.2;
	k.maxSize = 0.6;
	k.minWidth = 0.12;
	k.maxWidth = 0.55;
	k.minTop = 0.2;
	k.maxTop = 0.65;
	DetectionPass nearPass;
	nearPass.rowBegin = 0;
	nearPass.rowEnd = 211;
	nearPass.minSide = 20;
	const double step = 0.5 * M_PI / 180;
	ObjectProposal p;
	p.box = cv::Rect(100, 30, 20, 25);  // 2 m away: 0.35 x 0.44 m
	p.nearRange = 2.0;
	p.farRange = 2.1;
	p.bottom = 0.02;
	p.top = 0.4;
	const auto regs =
	    det.searchRegions(k, nearPass, {20, 20}, {p}, {361, 211}, step);
	ASSERT_EQ(regs.size(), 1u);
	const auto& r = regs[0];
	// Sides: the class's sizes at this range, the box filling 50 % to all
	// of the window (1.15 x larger side), with the slack.
	const double expectLo = std::max(
	    {20.0, 1.15 * 0.3 / 2.1 / step / 1.15, 1.15 * 0.5 * 25 / 1.15});
	const double expectHi =
	    std::min(1.15 * 0.6 / 2.0 / step * 1.15, 1.15 * 1.15 * 25 + 2);
	EXPECT_NEAR(r.minSide, expectLo, 1e-9);
	EXPECT_NEAR(r.maxSide, expectHi, 1e-9);
	EXPECT_EQ(r.rect & p.box, p.box);
	EXPECT_GE(r.rect.width, r.maxSide);
	EXPECT_GE(r.rect.height, r.maxSide);
	EXPECT_LT(r.rect.area(), 4 * 25 * 25);
	// A far pass over rows [0, 40) only searches the band.
	DetectionPass farPass = nearPass;
	farPass.rowEnd = 40;
	farPass.upscale = 3;
	farPass.minSide = 20.0 / 3;
	farPass.maxSide = 24;
	const auto far =
	    det.searchRegions(k, farPass, {20, 20}, {p}, {361, 211}, step);
	ASSERT_EQ(far.size(), 1u);
	EXPECT_LE(far[0].rect.y + far[0].rect.height, 40);
	EXPECT_LE(far[0].maxSide, 24);
	// Too low to hold a wastebasket's top: no search.
	ObjectProposal flat = p;
	flat.top = 0.1;
	EXPECT_TRUE(
	    det.searchRegions(k, nearPass, {20, 20}, {flat}, {361, 211}, step)
	        .empty());
	// 10 m away the class is smaller than the window: not in the near pass.
	ObjectProposal far10 = p;
	far10.nearRange = far10.farRange = 10;
	far10.box = cv::Rect(100, 30, 4, 5);
	EXPECT_TRUE(
	    det.searchRegions(k, nearPass, {20, 20}, {far10}, {361, 211}, step)
	        .empty());
}

TEST(DetectorProposals, OptionsRoundTripAndRangeErrors)
{
	const auto load = [](const std::string& text)
	{
		mrpt::config::CConfigFileMemory c(text);
		CascadeDetector::TOptions o;
		o.loadFromConfigFile(c, "CascadeDetector");
		return o;
	};
	const auto o = load(
	    "[CascadeDetector]\nclasses = stairs\nproposals = false\n"
	    "proposal_fill = 0.3\nproposal_size_slack = 1.4\n"
	    "proposal_range_gap_m = 0.7\n[CascadeDetector.stairs]\n"
	    "min_size_m = 0.9\nmax_size_m = 2.5\nborder_px = 16\n"
	    "proposal_min_neighbors = 1\n");
	EXPECT_FALSE(o.proposals);
	EXPECT_DOUBLE_EQ(o.proposalFill, 0.3);
	EXPECT_DOUBLE_EQ(o.proposalSizeSlack, 1.4);
	EXPECT_DOUBLE_EQ(o.proposalRangeGap, 0.7);
	EXPECT_DOUBLE_EQ(o.classes[0].minSize, 0.9);
	EXPECT_DOUBLE_EQ(o.classes[0].maxSize, 2.5);
	EXPECT_DOUBLE_EQ(o.classes[0].borderPx, 16);
	EXPECT_EQ(o.classes[0].proposalMinNeighbors, 1);
	CascadeDetector::TOptions back = test::savedAndLoaded(o, "CascadeDetector");
	EXPECT_EQ(back.proposals, o.proposals);
	EXPECT_DOUBLE_EQ(back.proposalFill, o.proposalFill);
	EXPECT_DOUBLE_EQ(back.proposalMargin, o.proposalMargin);
	EXPECT_DOUBLE_EQ(back.proposalTopMargin, o.proposalTopMargin);
	EXPECT_EQ(back.proposalJoinPx, o.proposalJoinPx);
	EXPECT_DOUBLE_EQ(back.classes[0].minCutSize, o.classes[0].minCutSize);
	EXPECT_DOUBLE_EQ(back.classes[0].borderPx, 16);
	EXPECT_EQ(back.classes[0].proposalMinNeighbors, 1);
	EXPECT_THROW(load("[CascadeDetector]\nproposal_fill = 1.5\n"), ConfigError);
	EXPECT_THROW(
	    load("[CascadeDetector]\nproposal_size_slack = 0.9\n"), ConfigError);
	EXPECT_THROW(load("[CascadeDetector]\nproposal_fil = 0.5\n"), ConfigError);
	EXPECT_THROW(
	    load("[CascadeDetector]\nclasses = stairs\n[CascadeDetector.stairs]\n"
	         "min_size_m = 3\nmax_size_m = 2\n"),
	    ConfigError);
}
