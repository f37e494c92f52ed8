/* semnav: semantic navigation from tilting-laser sweeps */
// What the localization rebuilds after each insertion, updated around the
// changed cells only, equals a rebuild of the whole map: on random changes
// recorded with markChanged() and on real insertions (the grid growing).
#include <gtest/gtest.h>
#include <semnav/common/LabelSet.h>
#include <semnav/localization/Localizer.h>
#include <semnav/localization/SemanticEvidenceMap.h>
#include <semnav/localization/WallMap.h>
#include <semnav/map/SemanticMap.h>

#include <random>

#include "../map/MapTestUtils.h"

using namespace semnav;

namespace
{
const std::vector<Label> kLabels = {
    Label::Floor,     Label::Door,     Label::Wastebasket,
    Label::Washbasin, Label::Obstacle, Label::Stairs,
    Label::Wall,      Label::Grass,    Label::Sidewalk};

/** Expects the same fields and objects. */
void expectSame(
    const SemanticEvidenceMap& a, const SemanticEvidenceMap& b,
    const std::string& when)
{
	for (const Label l : allLabels())
	{
		ASSERT_EQ(a.hasField(l), b.hasField(l)) << labelName(l) << " " << when;
		ASSERT_TRUE(a.field(l) == b.field(l)) << labelName(l) << " " << when;
	}
}

/** A point of each kind of label seen by a sweep at `pose` (a fan of floor,
 * an obstacle or bin face, a door strip). */
test::FakeSweep randomSweep(std::mt19937& rng)
{
	std::uniform_real_distribution<double> u(0, 1);
	auto pts = test::floorFan(1.5 + 2 * u(rng), 0.05);
	const Label face = kLabels[rng() % kLabels.size()];
	const double fx = 1 + 2 * u(rng), fy = u(rng) - 0.5;
	for (double y = -0.2; y <= 0.2; y += 0.03)
		for (double z = 0.1; z <= 0.8; z += 0.1)
			pts.push_back({fx, fy + y, z, face});
	return test::makeFakeSweep(pts);
}

/** Inserts a random sweep at a random pose, mostly inside what was seen,
 * every 6th beyond (the grid grows); returns the pose. */
mrpt::poses::CPose2D insertRandomSweep(
    SemanticMap& map, std::mt19937& rng, int k)
{
	std::uniform_real_distribution<double> u(0, 1);
	const auto f = randomSweep(rng);
	const double reach = k % 6 == 5 ? 8 : 2;
	const mrpt::poses::CPose2D pose(
	    reach * u(rng), reach * u(rng), 2 * M_PI * u(rng));
	map.insert(f.sweep, f.labeled, pose);
	return pose;
}
}  // namespace

TEST(IncrementalRebuild, EvidenceOnRandomChangesEqualsAFullBuild)
{
	std::mt19937 rng(7);
	for (const bool flatOnly : {false, true})
	{
		SemanticMap map;
		map.growToInclude(0, 0, 8, 6);
		const GridGeometry g = map.geometry();
		// Written through held references; each batch recorded with
		// markChanged().
		auto& labels = map.get("labels");
		auto& seen = map.get("observations");
		for (int cy = 0; cy < g.rows; cy++)
			for (int cx = 0; cx < g.cols / 2; cx++)
			{
				LabelSet floor;
				floor.insert(Label::Floor);
				labels[g.index(cy, cx)] = static_cast<float>(floor.mask());
				seen[g.index(cy, cx)] = 1;
			}
		SemanticEvidenceMap incremental, full;
		incremental.build(map, flatOnly);
		for (int k = 0; k < 40; k++)
		{
			const int w = 1 + static_cast<int>(rng() % 25);
			const int h = 1 + static_cast<int>(rng() % 25);
			const int c0 = static_cast<int>(rng() % (g.cols - w));
			const int r0 = static_cast<int>(rng() % (g.rows - h));
			for (int n = 0; n < w * h / 3; n++)
			{
				const int cx = c0 + static_cast<int>(rng() % w);
				const int cy = r0 + static_cast<int>(rng() % h);
				LabelSet ls(
				    static_cast<LabelSet::mask_t>(labels[g.index(cy, cx)]));
				ls.insert(kLabels[rng() % kLabels.size()]);
				// Now and then a label goes (an edit, not an insertion).
				if (rng() % 50 == 0) ls = LabelSet();
				labels[g.index(cy, cx)] = static_cast<float>(ls.mask());
				seen[g.index(cy, cx)] += 1;
			}
			map.markChanged({r0, c0, r0 + h, c0 + w});
			incremental.update(map, flatOnly);
			full.build(map, flatOnly);
			expectSame(incremental, full, "change " + std::to_string(k));
		}
	}
}

TEST(IncrementalRebuild, EvidenceAfterInsertionsEqualsAFullBuild)
{
	std::mt19937 rng(11);
	SemanticMap map;
	SemanticEvidenceMap incremental, full;
	for (int k = 0; k < 30; k++)
	{
		insertRandomSweep(map, rng, k);
		incremental.update(map);
		full.build(map);
		expectSame(incremental, full, "sweep " + std::to_string(k));
	}
}

namespace
{
void expectSameWalls(
    const WallMap& a, const WallMap& b, const std::string& when)
{
	ASSERT_TRUE(a.geometry() == b.geometry()) << when;
	ASSERT_TRUE(a.field() == b.field()) << when;
	ASSERT_EQ(a.segments().size(), b.segments().size()) << when;
	for (std::size_t k = 0; k < a.segments().size(); k++)
	{
		ASSERT_EQ(a.segments()[k].p0, b.segments()[k].p0) << when;
		ASSERT_EQ(a.segments()[k].p1, b.segments()[k].p1) << when;
	}
	ASSERT_EQ(a.mainDirection(), b.mainDirection()) << when;
	const mrpt::poses::CPose2D pose(2, 1, 0.3);
	std::vector<mrpt::math::TPoint2D> pts;
	for (double x = -3; x < 3; x += 0.07) pts.push_back({x, 0.5 * x});
	ASSERT_EQ(a.inlierFraction(pose, pts), b.inlierFraction(pose, pts)) << when;
}
}  // namespace

TEST(IncrementalRebuild, WallsOfRandomChangesEqualAFullBuild)
{
	std::mt19937 rng(5);
	for (const bool unknown : {false, true})
	{
		SemanticMap map;
		map.growToInclude(0, 0, 14, 9);
		const GridGeometry g = map.geometry();
		auto& labels = map.get("labels");
		auto& seen = map.get("observations");
		WallMap incremental;
		incremental.buildFromSemanticMap(map, unknown);
		for (int k = 0; k < 30; k++)
		{
			// A wall stretch (some cells lose it), cells observed.
			const bool vertical = rng() % 2;
			const int len = 5 + static_cast<int>(rng() % 60);
			const int c0 = static_cast<int>(rng() % (g.cols - len));
			const int r0 = static_cast<int>(rng() % (g.rows - len));
			CellRect rect;
			for (int t = 0; t < len; t++)
			{
				const int cx = vertical ? c0 : c0 + t;
				const int cy = vertical ? r0 + t : r0;
				LabelSet ls(
				    static_cast<LabelSet::mask_t>(labels[g.index(cy, cx)]));
				if (rng() % 8 == 0)
					ls.erase(Label::Wall);
				else
					ls.insert(Label::Wall);
				labels[g.index(cy, cx)] = static_cast<float>(ls.mask());
				seen[g.index(cy, cx)] += 1;
				rect.add(cy, cx);
			}
			map.markChanged(rect);
			incremental.updateFromSemanticMap(map, unknown);
			WallMap full;
			full.buildFromSemanticMap(map, unknown);
			expectSameWalls(incremental, full, "change " + std::to_string(k));
		}
	}
}

TEST(IncrementalRebuild, MappingWallsAfterInsertionsEqualARebuild)
{
	std::mt19937 rng(3);
	std::uniform_real_distribution<double> u(0, 1);
	SemanticMap map;
	WallMap incremental;
	std::vector<WallSegment> all;
	for (int k = 0; k < 25; k++)
	{
		const mrpt::poses::CPose2D pose = insertRandomSweep(map, rng, k);
		// A wall seen at the pose (robot frame), now and then none.
		std::vector<WallSegment> seenWalls;
		for (int n = static_cast<int>(rng() % 3); n > 0; n--)
		{
			WallSegment s;
			s.p0 = {1 + 2 * u(rng), -2 + 4 * u(rng)};
			s.p1 = {s.p0.x + 3 * u(rng) - 1.5, s.p0.y + 3 * u(rng) - 1.5};
			seenWalls.push_back(s);
			all.push_back(s.transformed(pose));
		}
		incremental.addObservation(seenWalls, pose);
		incremental.update(map);
		WallMap full;
		full.addSegments(all);
		full.rebuild(&map);
		if (all.empty()) continue;
		expectSameWalls(incremental, full, "sweep " + std::to_string(k));
	}
}

TEST(IncrementalRebuild, KnownMapAfterInsertionsEqualsSetKnownMap)
{
	std::mt19937 rng(13);
	SemanticMap map;
	Localizer incremental;
	for (int k = 0; k < 20; k++)
	{
		insertRandomSweep(map, rng, k);
		if (k == 0)
			incremental.setKnownMap(map);
		else
			incremental.updateKnownMap(map);
		Localizer full;
		full.setKnownMap(map);
		const std::string when = "sweep " + std::to_string(k);
		expectSameWalls(incremental.knownWallMap(), full.knownWallMap(), when);
		// The same free cells: the same global start from the same seed
		// (a Localizer seeds MRPT's shared generator when made).
		Localizer{incremental.options()};
		incremental.initializeGlobal();
		const auto first = incremental.pdf().m_particles;
		Localizer{full.options()};
		full.initializeGlobal();
		ASSERT_EQ(first.size(), full.pdf().m_particles.size()) << when;
		for (std::size_t i = 0; i < first.size(); i += 97)
			ASSERT_EQ(first[i].d, full.pdf().m_particles[i].d) << when;
	}
}
