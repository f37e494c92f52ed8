/* semnav: semantic navigation from tilting-laser sweeps */
// The shipped cascades and shape forests on real tilting-LMS200 scans (3DTK,
// ../shared/data/3dtk/): an outdoor arcade of floor, roof, wall, pillars,
// arches and steps. What can be known without labels: every class gets
// measured candidates and reaches the shape check on some scan, and no
// wastebasket is found. (A washbasin is found on scan001, on a pillar with a
// railing: a known false alarm, docs/detection.md.)
#include <gtest/gtest.h>
#include <semnav/detection/CascadeDetector.h>
#include <semnav/perception/PerceptionPipeline.h>
#include <semnav/scan/ThreeDtkReader.h>

#include <cstdio>
#include <filesystem>
#include <map>

#include "../TestPaths.h"
#include "../common/ThreeDtkData.h"

using namespace semnav;
namespace fs = std::filesystem;

namespace
{

class ThreeDtkDetection : public ::testing::TestWithParam<const char*>
{
protected:
	/** The detector's candidates on the scan. */
	std::vector<CascadeDetector::Candidate> candidates()
	{
		const Sweep sw =
		    ThreeDtkReader().read((test::kThreeDtkDir / GetParam()).string());
		PerceptionPipeline pipeline;
		const LabeledSweep ls = pipeline.process(sw);
		CascadeDetector detector(CascadeDetector::TOptions::fromIniFile(
		    (fs::path(test::kSourceDir) / "config" / "cascade.ini").string()));
		return detector.detectCandidates(
		    sw.phis(), sw.thetas(), ls.normals, ls.normalMask, ls.points,
		    ls.groundZ, ls.labels, ls.areaIds);
	}
};
}  // namespace

TEST_P(ThreeDtkDetection, EveryClassGetsMeasuredCandidates)
{
	SKIP_WITHOUT_3DTK(GetParam());
	std::map<Label, int> measured;
	for (const auto& c : candidates())
	{
		measured[c.label] += c.measure.has_value();
		if (c.accepted)
			std::printf(
			    "%s: %s accepted at %.2f, %.2f (shape score %.2f)\n",
			    GetParam(), labelName(c.label).c_str(), c.measure->centroid.x,
			    c.measure->centroid.y, c.shapeScore);
	}
	for (Label l : {Label::Washbasin, Label::Wastebasket, Label::Stairs})
		EXPECT_GT(measured[l], 0) << labelName(l);
}

/** The shape check runs on real scans for every class, on one scan at least
 * (an arcade has no washbasin: with the wall rules of issue 40 scan000's
 * washbasin candidates all fail the geometric checks before it). */
TEST(ThreeDtkDetectionScans, EveryClassReachesTheShapeCheckOnSomeScan)
{
	std::map<Label, int> scored;
	int scans = 0;
	for (const char* scan : {"scan000.3d", "scan001.3d"})
	{
		const fs::path path = test::kThreeDtkDir / scan;
		if (!fs::exists(path)) continue;
		scans++;
		const Sweep sw = ThreeDtkReader().read(path.string());
		const LabeledSweep ls = PerceptionPipeline().process(sw);
		CascadeDetector detector(CascadeDetector::TOptions::fromIniFile(
		    (fs::path(test::kSourceDir) / "config" / "cascade.ini").string()));
		for (const auto& c : detector.detectCandidates(
		         sw.phis(), sw.thetas(), ls.normals, ls.normalMask, ls.points,
		         ls.groundZ, ls.labels, ls.areaIds))
			scored[c.label] += c.shape.has_value();
	}
	if (scans == 0) GTEST_SKIP() << "3DTK data not found";
	for (Label l : {Label::Washbasin, Label::Wastebasket, Label::Stairs})
	{
		EXPECT_GT(scored[l], 0) << labelName(l);
		std::printf(
		    "%s: %d candidates shape-scored over %d scans\n",
		    labelName(l).c_str(), scored[l], scans);
	}
}

TEST_P(ThreeDtkDetection, NoWastebasketInTheArcade)
{
	SKIP_WITHOUT_3DTK(GetParam());
	int scored = 0;
	for (const auto& c : candidates())
	{
		if (c.label != Label::Wastebasket) continue;
		scored += c.shape.has_value();
		EXPECT_FALSE(c.accepted)
		    << "wastebasket at " << c.measure->centroid.x << ", "
		    << c.measure->centroid.y << " (shape score " << c.shapeScore << ")";
	}
	// Whether the forest is reached is checked over both scans by
	// EveryClassReachesTheShapeCheckOnSomeScan: with the wall plane reclaim
	// scan000's wastebasket candidates all fail the geometric checks first.
	std::printf(
	    "%s: %d wastebasket candidates shape-scored\n", GetParam(), scored);
}

INSTANTIATE_TEST_SUITE_P(
    Scans, ThreeDtkDetection, ::testing::Values("scan000.3d", "scan001.3d"));
