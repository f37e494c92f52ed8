/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <semnav/common/Error.h>
#include <semnav/perception/RangeSegmentation.h>

#include <map>
#include <opencv2/core.hpp>
#include <set>

#include "SyntheticScene.h"

using namespace semnav;
using namespace semnav::test;

namespace
{
/** Area id holding most pixels of true label `l` (and how many). */
std::pair<int, int> dominantArea(
    const cv::Mat& ids, const cv::Mat& truth, Label l)
{
	std::map<int, int> n;
	for (int r = 0; r < ids.rows; r++)
		for (int c = 0; c < ids.cols; c++)
			if (truth.at<uint8_t>(r, c) == static_cast<uint8_t>(l))
				n[ids.at<int>(r, c)]++;
	std::pair<int, int> best{0, 0};
	for (auto [id, k] : n)
		if (id > 0 && k > best.second) best = {id, k};
	return best;
}
}  // namespace

TEST(RangeSegmentation, AreasAreNumberedConnectedAndLargeEnough)
{
	SynthScene sc = boxRoom(-3, 5, -2, 2.5, 2.5);
	sc.noise = 0.005;
	const Sweep sw = renderSweep(sc);
	RangeSegmentation seg;
	seg.compute(sw);
	const cv::Mat& ids = seg.areaIds();
	ASSERT_EQ(ids.rows, static_cast<int>(sw.rows()));
	ASSERT_GE(seg.areaCount(), 1);

	// Sizes add up, every area > 30 px, ids 1..n all used, invalid -> 0.
	std::vector<int> count(seg.areaCount() + 1, 0);
	for (int r = 0; r < ids.rows; r++)
		for (int c = 0; c < ids.cols; c++)
		{
			const int id = ids.at<int>(r, c);
			ASSERT_GE(id, 0);
			ASSERT_LE(id, seg.areaCount());
			count[id]++;
			if (!sw.valid(r, c)) EXPECT_EQ(id, 0);
		}
	int total = 0;
	for (int i = 0; i <= seg.areaCount(); i++)
	{
		EXPECT_EQ(count[i], seg.areaSizes()[i]) << "area " << i;
		if (i > 0) EXPECT_GT(count[i], 30) << "area " << i;
		total += count[i];
	}
	EXPECT_EQ(total, ids.rows * ids.cols);

	// Each area is 4-connected through neighbours within 5 cm of range.
	for (int id = 1; id <= seg.areaCount(); id++)
	{
		cv::Mat seen(ids.size(), CV_8U, cv::Scalar(0));
		std::vector<cv::Point> stack;
		for (int r = 0; r < ids.rows && stack.empty(); r++)
			for (int c = 0; c < ids.cols && stack.empty(); c++)
				if (ids.at<int>(r, c) == id) stack.push_back({c, r});
		int reached = 0;
		seen.at<uint8_t>(stack[0]) = 1;
		while (!stack.empty())
		{
			const cv::Point p = stack.back();
			stack.pop_back();
			reached++;
			for (cv::Point d :
			     {cv::Point(1, 0), cv::Point(-1, 0), cv::Point(0, 1),
			      cv::Point(0, -1)})
			{
				const cv::Point q = p + d;
				if (q.x < 0 || q.y < 0 || q.x >= ids.cols || q.y >= ids.rows)
					continue;
				if (seen.at<uint8_t>(q) || ids.at<int>(q) != id) continue;
				if (std::abs(sw.range(q.y, q.x) - sw.range(p.y, p.x)) >
				    0.05f + 1e-6f)
					continue;
				seen.at<uint8_t>(q) = 1;
				stack.push_back(q);
			}
		}
		EXPECT_EQ(reached, count[id])
		    << "area " << id << " is not one flood fill";
	}
}

TEST(RangeSegmentation, FloorWallsCeilingFloodTogetherAnObjectApart)
{
	// The paper: walls, ceiling and floor end up in one area (small range
	// steps at the corners); an object standing off the wall (range jump)
	// is another area.
	SynthScene sc = boxRoom(-3, 5, -2, 2.5, 2.5);
	sc.boxes.push_back(
	    {{2.0, -0.5, 0.8}, {2.4, 0.5, 1.6}, Label::Obstacle});  // floating box
	cv::Mat truth;
	const Sweep sw = renderSweep(sc, &truth);
	RangeSegmentation seg;
	seg.compute(sw);
	const auto floor = dominantArea(seg.areaIds(), truth, Label::Floor);
	const auto wall = dominantArea(seg.areaIds(), truth, Label::Wall);
	const auto ceiling = dominantArea(seg.areaIds(), truth, Label::Ceiling);
	const auto box = dominantArea(seg.areaIds(), truth, Label::Obstacle);
	ASSERT_GT(floor.first, 0);
	EXPECT_EQ(floor.first, wall.first);
	EXPECT_EQ(wall.first, ceiling.first);
	ASSERT_GT(box.first, 0);
	EXPECT_NE(box.first, wall.first);
}

TEST(RangeSegmentation, SmallAreasAndThresholdFollowTheOptions)
{
	SynthScene sc = boxRoom(-3, 5, -2, 2.5, 2.5);
	sc.noise = 0.02;
	const Sweep sw = renderSweep(sc);
	RangeSegmentation::TOptions o;
	RangeSegmentation coarse(o);
	coarse.compute(sw);
	o.maxNeighbourDifference = 0.01;  // 2 cm noise: most neighbours differ more
	RangeSegmentation fine(o);
	fine.compute(sw);
	EXPECT_GT(fine.areaSizes()[0], coarse.areaSizes()[0]);
	EXPECT_GT(
	    fine.fills() + fine.singletons(), coarse.fills() + coarse.singletons());
	o.maxNeighbourDifference = 0.05;
	o.minAreaPixels = 1000000;  // nothing is that large
	RangeSegmentation none(o);
	none.compute(sw);
	EXPECT_EQ(none.areaCount(), 0);
	EXPECT_EQ(none.areaSizes()[0], static_cast<int>(sw.rows() * sw.cols()));
}

TEST(RangeSegmentation, BadInput)
{
	RangeSegmentation seg;
	seg.compute(Sweep());
	EXPECT_EQ(seg.areaCount(), 0);
	EXPECT_TRUE(seg.areaIds().empty());
	seg.compute(Sweep(211, 361));
	EXPECT_EQ(seg.areaCount(), 0);
	EXPECT_EQ(cv::countNonZero(seg.areaIds()), 0);
	// NaN ranges flagged valid never join an area.
	Sweep sw = renderSweep(boxRoom(-3, 5, -2, 2.5, 2.5));
	for (std::size_t c = 0; c < sw.cols(); c++)
		sw.setRange(100, c, std::numeric_limits<float>::quiet_NaN(), true);
	seg.compute(sw);
	for (int c = 0; c < static_cast<int>(sw.cols()); c++)
		EXPECT_EQ(seg.areaIds().at<int>(100, c), 0);
	EXPECT_GT(seg.areaCount(), 0);

	mrpt::config::CConfigFileMemory cfg;
	cfg.write("RangeSegmentation", "connectivity", 6);
	RangeSegmentation::TOptions o;
	EXPECT_THROW(o.loadFromConfigFile(cfg, "RangeSegmentation"), ConfigError);
}
