/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <semnav/common/Error.h>
#include <semnav/perception/NormalImage.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "../common/SavedAndLoaded.h"
#include "SyntheticScene.h"

using namespace semnav;
using namespace semnav::test;

namespace
{
/** Median (R, G, B) over the pixels of true label `l` that have a normal
 * and satisfy `where(point)`. */
cv::Vec3b medianColour(
    const NormalImage& ni, const cv::Mat& truth, Label l,
    const std::function<bool(const cv::Vec3f&)>& where, std::size_t& count)
{
	std::vector<int> ch[3];
	for (int r = 0; r < truth.rows; r++)
		for (int c = 0; c < truth.cols; c++)
		{
			if (truth.at<uint8_t>(r, c) != static_cast<uint8_t>(l)) continue;
			if (!ni.normalMask().at<uint8_t>(r, c)) continue;
			if (!where(ni.points().at<cv::Vec3f>(r, c))) continue;
			const cv::Vec3b rgb =
			    NormalImage::rgbOf(ni.normals().at<cv::Vec3f>(r, c));
			for (int k = 0; k < 3; k++) ch[k].push_back(rgb[k]);
		}
	count = ch[0].size();
	cv::Vec3b out(0, 0, 0);
	for (int k = 0; k < 3; k++)
	{
		if (ch[k].empty()) return out;
		std::nth_element(
		    ch[k].begin(), ch[k].begin() + ch[k].size() / 2, ch[k].end());
		out[k] = static_cast<uint8_t>(ch[k][ch[k].size() / 2]);
	}
	return out;
}
}  // namespace

TEST(NormalImage, PaperColoursInABoxRoom)
{
	// Robot in a 8 m x 4.5 m room: the paper's colour description (sec. 2.1,
	// docs/design.md): floor blueish, ceiling yellowish, left wall pink, right
	// wall cyan, the wall ahead purple.
	SynthScene sc = boxRoom(-3, 5, -2, 2.5, 2.5);
	sc.noise = 0.005;
	cv::Mat truth;
	const Sweep sw = renderSweep(sc, &truth);
	NormalImage ni;
	ni.compute(sw);
	ASSERT_GT(ni.validNormals(), sw.validCount() / 2);

	std::size_t n = 0;
	const auto floor = medianColour(
	    ni, truth, Label::Floor, [](auto&) { return true; }, n);
	ASSERT_GT(n, 1000u);
	EXPECT_GT(floor[2], 230) << "floor should be blue";
	EXPECT_NEAR(floor[0], 128, 15);
	EXPECT_NEAR(floor[1], 128, 15);

	const auto ceiling = medianColour(
	    ni, truth, Label::Ceiling, [](auto&) { return true; }, n);
	ASSERT_GT(n, 1000u);
	EXPECT_LT(ceiling[2], 25) << "ceiling should be yellowish (blue low)";
	EXPECT_NEAR(ceiling[0], 128, 15);
	EXPECT_NEAR(ceiling[1], 128, 15);

	const auto left = medianColour(
	    ni, truth, Label::Wall, [](const cv::Vec3f& p) { return p[1] > 2.4f; },
	    n);
	ASSERT_GT(n, 500u);
	EXPECT_GT(left[0], 230) << "left wall should be pink (red high)";
	EXPECT_NEAR(left[1], 128, 15);
	EXPECT_NEAR(left[2], 128, 15);

	const auto right = medianColour(
	    ni, truth, Label::Wall, [](const cv::Vec3f& p) { return p[1] < -1.9f; },
	    n);
	ASSERT_GT(n, 500u);
	EXPECT_LT(right[0], 25) << "right wall should be cyan (red low)";
	EXPECT_NEAR(right[1], 128, 15);
	EXPECT_NEAR(right[2], 128, 15);

	const auto ahead = medianColour(
	    ni, truth, Label::Wall, [](const cv::Vec3f& p) { return p[0] > 4.9f; },
	    n);
	ASSERT_GT(n, 500u);
	EXPECT_LT(ahead[1], 25) << "wall facing the robot should be purple";
	EXPECT_NEAR(ahead[0], 128, 15);
	EXPECT_NEAR(ahead[2], 128, 15);

	// The BGR image carries the same colours.
	const cv::Mat bgr = ni.toBgr();
	ASSERT_EQ(bgr.rows, static_cast<int>(sw.rows()));
	ASSERT_EQ(bgr.cols, static_cast<int>(sw.cols()));
	for (int r = 0; r < bgr.rows; r += 7)
		for (int c = 0; c < bgr.cols; c += 7)
		{
			const cv::Vec3b px = bgr.at<cv::Vec3b>(r, c);
			if (!ni.normalMask().at<uint8_t>(r, c))
			{
				EXPECT_EQ(px, cv::Vec3b(0, 0, 0));
				continue;
			}
			const cv::Vec3b rgb =
			    NormalImage::rgbOf(ni.normals().at<cv::Vec3f>(r, c));
			EXPECT_EQ(px, cv::Vec3b(rgb[2], rgb[1], rgb[0]));
		}
}

TEST(NormalImage, NormalsAreUnitExactAndFaceTheSensor)
{
	SynthScene sc = boxRoom(-3, 5, -2, 2.5, 2.5);  // no noise
	cv::Mat truth;
	const Sweep sw = renderSweep(sc, &truth);
	NormalImage ni;
	ni.compute(sw);
	std::size_t checked = 0;
	for (int r = 1; r + 1 < truth.rows; r++)
		for (int c = 1; c + 1 < truth.cols; c++)
		{
			if (!ni.normalMask().at<uint8_t>(r, c)) continue;
			const cv::Vec3f n = ni.normals().at<cv::Vec3f>(r, c);
			const cv::Vec3f p = ni.points().at<cv::Vec3f>(r, c);
			ASSERT_NEAR(cv::norm(n), 1.0, 1e-4);
			EXPECT_GT(n.dot(ni.sensorPositions()[r] - p), 0.0f);
			// Points agree with Sweep::point().
			const auto q = sw.point(r, c);
			ASSERT_NEAR(p[0], q.x, 1e-4);
			ASSERT_NEAR(p[2], q.z, 1e-4);
			// Away from edges (all four diagonal neighbours on the same
			// plane) a noise-free floor has n = (0, 0, 1).
			bool sameFloor =
			    truth.at<uint8_t>(r, c) == static_cast<uint8_t>(Label::Floor);
			for (int dr : {-1, 1})
				for (int dc : {-1, 1})
					sameFloor =
					    sameFloor && truth.at<uint8_t>(r + dr, c + dc) ==
					                     static_cast<uint8_t>(Label::Floor);
			if (sameFloor)
			{
				EXPECT_NEAR(n[2], 1.0, 1e-3);
				checked++;
			}
		}
	EXPECT_GT(checked, 1000u);
}

TEST(NormalImage, NeighboursOutsideEps0Eps1AreRejected)
{
	// Far floor rows are more than eps1 = 30 cm apart: no normal there; the
	// near floor (rows a few cm apart) has normals.
	SynthScene sc;
	sc.maxRange = 30;
	cv::Mat truth;
	const Sweep sw = renderSweep(sc, &truth);
	NormalImage ni;
	ni.compute(sw);
	const int c = 180;  // straight ahead
	std::size_t nearWith = 0, farWithout = 0, far = 0;
	for (int r = 0; r + 1 < truth.rows; r++)
	{
		if (!sw.valid(r, c) || !sw.valid(r + 1, c)) continue;
		const auto p = sw.point(r, c), q = sw.point(r + 1, c);
		const double gap = std::hypot(p.x - q.x, p.y - q.y, p.z - q.z);
		if (gap < 0.2) nearWith += ni.normalMask().at<uint8_t>(r, c);
		if (gap > 0.6)
		{
			far++;
			farWithout += !ni.normalMask().at<uint8_t>(r, c);
		}
	}
	EXPECT_GT(nearWith, 5u);
	ASSERT_GT(far, 3u);
	EXPECT_EQ(farWithout, far);

	// With eps1 raised the far rows get normals too.
	NormalImage::TOptions o;
	o.maxNeighbourDistance = 5.0;
	NormalImage wide(o);
	wide.compute(sw);
	EXPECT_GT(wide.validNormals(), ni.validNormals());
}

TEST(NormalImage, BadInputGivesNoNormalsAndNoCrash)
{
	NormalImage ni;
	ni.compute(Sweep());
	EXPECT_EQ(ni.validNormals(), 0u);
	EXPECT_EQ(ni.rows(), 0u);
	EXPECT_TRUE(ni.toBgr().empty());

	Sweep allInvalid(211, 361);
	ni.compute(allInvalid);
	EXPECT_EQ(ni.validPoints(), 0u);
	EXPECT_EQ(ni.validNormals(), 0u);
	EXPECT_EQ(ni.toBgr().rows, 211);

	// Ranges flagged valid but NaN, infinite or negative count as invalid.
	SynthScene sc = boxRoom(-3, 5, -2, 2.5, 2.5);
	Sweep sw = renderSweep(sc);
	const std::size_t before = sw.validCount();
	for (std::size_t c = 0; c < sw.cols(); c += 3)
	{
		sw.setRange(50, c, std::numeric_limits<float>::quiet_NaN(), true);
		sw.setRange(51, c, std::numeric_limits<float>::infinity(), true);
		sw.setRange(52, c, -1.0f, true);
	}
	ni.compute(sw);
	EXPECT_EQ(ni.validPoints(), before - 3 * ((sw.cols() + 2) / 3));
	for (std::size_t c = 0; c < sw.cols(); c += 3)
	{
		EXPECT_FALSE(ni.pointMask().at<uint8_t>(50, static_cast<int>(c)));
		EXPECT_FALSE(ni.normalMask().at<uint8_t>(51, static_cast<int>(c)));
	}
	for (int r = 0; r < ni.normals().rows; r++)
		for (int c = 0; c < ni.normals().cols; c++)
		{
			const cv::Vec3f n = ni.normals().at<cv::Vec3f>(r, c);
			ASSERT_TRUE(
			    std::isfinite(n[0]) && std::isfinite(n[1]) &&
			    std::isfinite(n[2]));
		}

	// One row: no vertical neighbours, so no normal, but points.
	SynthScene one = boxRoom(-3, 5, -2, 2.5, 2.5);
	one.thetaMinDeg = one.thetaMaxDeg = 10;
	const Sweep row = renderSweep(one);
	ASSERT_EQ(row.rows(), 1u);
	ni.compute(row);
	EXPECT_GT(ni.validPoints(), 300u);
	EXPECT_EQ(ni.validNormals(), 0u);
}

TEST(NormalImage, OptionsAreCheckedAndRoundTrip)
{
	mrpt::config::CConfigFileMemory cfg;
	cfg.write("NormalImage", "max_neighbour_distance_m", 0.5);
	cfg.write("NormalImage", "min_pair_angle_deg", 10);
	NormalImage::TOptions o;
	o.loadFromConfigFile(cfg, "NormalImage");
	EXPECT_DOUBLE_EQ(o.maxNeighbourDistance, 0.5);
	EXPECT_NEAR(o.minPairAngle, 10 * M_PI / 180, 1e-12);

	const NormalImage::TOptions back = test::savedAndLoaded(o, "NormalImage");
	EXPECT_DOUBLE_EQ(back.maxNeighbourDistance, 0.5);
	EXPECT_NEAR(back.minPairAngle, o.minPairAngle, 1e-12);

	mrpt::config::CConfigFileMemory bad;
	bad.write("NormalImage", "max_neighbor_distance_m", 0.5);  // typo
	EXPECT_THROW(o.loadFromConfigFile(bad, "NormalImage"), ConfigError);
	mrpt::config::CConfigFileMemory range;
	range.write("NormalImage", "min_pair_angle_deg", 60);
	EXPECT_THROW(o.loadFromConfigFile(range, "NormalImage"), ConfigError);
	mrpt::config::CConfigFileMemory order;
	order.write("NormalImage", "min_neighbour_distance_m", 0.4);
	order.write("NormalImage", "max_neighbour_distance_m", 0.3);
	EXPECT_THROW(o.loadFromConfigFile(order, "NormalImage"), ConfigError);
}

TEST(NormalImage, WidenedSideRowStepsKeepPlanesAndAreChecked)
{
	// side_row_step_max (default off): 0 leaves every normal as it was; 16
	// changes only the side columns of classifierNormals(), whose normals
	// on a noise-free plane equal the paper's and face the sensor, and
	// leaves normals() (the detectors' normals) bit for bit the paper's.
	SynthScene sc = boxRoom(-3, 5, -2, 2.5, 2.5);
	cv::Mat truth;
	const Sweep sw = renderSweep(sc, &truth);
	NormalImage off;
	off.compute(sw);
	NormalImage::TOptions o;
	o.sideRowStepMax = 16;
	NormalImage on(o);
	on.compute(sw);
	EXPECT_FALSE(off.widened());
	EXPECT_EQ(off.classifierNormals().data, off.normals().data);
	ASSERT_TRUE(on.widened());
	EXPECT_EQ(cv::norm(on.normals(), off.normals(), cv::NORM_INF), 0.0);
	EXPECT_EQ(cv::norm(on.normalMask(), off.normalMask(), cv::NORM_INF), 0.0);
	EXPECT_EQ(on.validNormals(), off.validNormals());
	std::size_t changedMiddle = 0, changedSide = 0, planeSide = 0;
	for (int r = 0; r < truth.rows; r++)
		for (int c = 0; c < truth.cols; c++)
		{
			const bool side = std::abs(std::cos(sw.phi(c))) < 0.5;
			const cv::Vec3f a = off.normals().at<cv::Vec3f>(r, c);
			const cv::Vec3f b = on.classifierNormals().at<cv::Vec3f>(r, c);
			if (!side && a != b) changedMiddle++;
			if (side && a != b) changedSide++;
			if (!side || !on.classifierNormalMask().at<uint8_t>(r, c)) continue;
			const cv::Vec3f p = on.points().at<cv::Vec3f>(r, c);
			ASSERT_NEAR(cv::norm(b), 1.0, 1e-4);
			EXPECT_GT(b.dot(on.sensorPositions()[r] - p), 0.0f);
			const int s = std::min(
			    16, static_cast<int>(1.0 / std::abs(std::cos(sw.phi(c)))));
			const uint8_t l = truth.at<uint8_t>(r, c);
			bool samePlane = off.normalMask().at<uint8_t>(r, c) != 0;
			for (int dr : {-s, -1, 1, s})
				for (int dc : {-1, 1})
					samePlane = samePlane && r + dr >= 0 &&
					            r + dr < truth.rows && c + dc >= 0 &&
					            c + dc < truth.cols &&
					            truth.at<uint8_t>(r + dr, c + dc) == l;
			if (samePlane)
			{
				EXPECT_GT(a.dot(b), 0.999f);
				planeSide++;
			}
		}
	EXPECT_EQ(changedMiddle, 0u);
	EXPECT_GT(changedSide, 0u);
	EXPECT_GT(planeSide, 0u);

	mrpt::config::CConfigFileMemory range;
	range.write("NormalImage", "side_row_step_max", 65);
	EXPECT_THROW(o.loadFromConfigFile(range, "NormalImage"), ConfigError);
}
