/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <semnav/localization/WallMap.h>
#include <semnav/map/SemanticMap.h>

#include "LocalizationTestUtils.h"

using namespace semnav;
using mrpt::DEG2RAD;

TEST(WallMap, LikelihoodPeaksAtTheTruePose)
{
	WallMap m;
	m.addSegments(test::roomWalls());
	m.rebuild();
	ASSERT_FALSE(m.empty());
	const mrpt::poses::CPose2D truth(3.0, 2.0, DEG2RAD(30));
	const auto obs = test::observe(test::roomWalls(), truth);
	const double at =
	    m.logLikelihood(truth.x(), truth.y(), truth.phi(), obs.samples);
	// Cells are 5 cm: a sample is at most half a cell off its wall.
	EXPECT_GT(at / obs.samples.size(), -0.1);
	EXPECT_DOUBLE_EQ(m.inlierFraction(truth, obs.samples), 1.0);
	for (const auto& d :
	     {mrpt::poses::CPose2D(0.1, 0, 0), mrpt::poses::CPose2D(0, -0.1, 0),
	      mrpt::poses::CPose2D(0, 0, DEG2RAD(2))})
	{
		const auto p = truth + d;
		EXPECT_LT(m.logLikelihood(p.x(), p.y(), p.phi(), obs.samples), at - 1);
	}
	const auto far = truth + mrpt::poses::CPose2D(0.8, 0.5, 0.3);
	EXPECT_LT(m.inlierFraction(far, obs.samples), 0.3);
	// Points outside the field get the floor value.
	EXPECT_FLOAT_EQ(m.logLikelihood(-50, -50), m.floorValue());
}

TEST(WallMap, MainDirectionOfARotatedRoom)
{
	WallMap m;
	m.addObservation(
	    test::roomWalls(), mrpt::poses::CPose2D(1, 2, DEG2RAD(-12)));
	m.rebuild();
	ASSERT_TRUE(m.mainDirection());
	EXPECT_NEAR(*m.mainDirection(), DEG2RAD(-12), 1e-6);
}

TEST(WallMap, FromSemanticMapWallCells)
{
	SemanticMap sm;
	sm.growToInclude(-1, -1, 11, 7);
	const auto& g = sm.geometry();
	// Rasterize the room's walls into the labels layer.
	LabelSet wall;
	wall.insert(Label::Wall);
	for (const auto& s : test::roomWalls())
		for (double t = 0; t <= 1; t += 0.005)
		{
			const auto p = s.p0 + (s.p1 - s.p0) * t;
			int cx, cy;
			if (sm.worldToCell(p.x, p.y, cx, cy))
				sm.at("labels", cx, cy) = static_cast<float>(wall.mask());
		}
	WallMap m;
	m.buildFromSemanticMap(sm);
	EXPECT_EQ(m.geometry(), g);
	ASSERT_TRUE(m.mainDirection());
	EXPECT_NEAR(*m.mainDirection(), 0.0, DEG2RAD(1));
	EXPECT_GE(m.segments().size(), 4u);
	const mrpt::poses::CPose2D truth(7.5, 3.0, DEG2RAD(-100));
	const auto obs = test::observe(test::roomWalls(), truth);
	EXPECT_GT(m.inlierFraction(truth, obs.samples), 0.95);
}

TEST(WallMap, UnobservedCellsAreNotMismatches)
{
	SemanticMap sm;
	sm.growToInclude(-1, -1, 11, 7);
	// Only x < 5 was observed.
	const auto& g = sm.geometry();
	for (int cy = 0; cy < g.rows; cy++)
		for (int cx = 0; cx < g.cols; cx++)
			if (g.centerX(cx) < 5) sm.at("observations", cx, cy) = 1;
	WallMap m;
	m.addSegments({test::seg(0, 0, 4, 0)});
	m.rebuild(&sm);
	// On the wall: best; far from it in observed space: worst; in
	// unobserved space: the unknown value, in between.
	EXPECT_GT(m.logLikelihood(2, 0.01), m.logLikelihood(8, 3));
	EXPECT_FLOAT_EQ(m.logLikelihood(2, 3), m.floorValue());
	EXPECT_FLOAT_EQ(m.logLikelihood(8, 3), std::log(m.options().unknownWeight));
	EXPECT_FLOAT_EQ(
	    m.logLikelihood(50, 50), std::log(m.options().unknownWeight));
	// Without an observed area every cell counts as observed.
	m.rebuild();
	EXPECT_FLOAT_EQ(m.logLikelihood(8, 3), m.floorValue());
}
