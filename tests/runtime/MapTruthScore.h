/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once
// A built map scored against a scene's truth (SceneMapBuilder's map of the
// scene): objects found per label, and how the occupancy the map observed
// agrees with the truth.
#include <semnav/map/SemanticMap.h>

#include <cmath>
#include <map>
#include <vector>

namespace semnav::test
{
struct MapTruthScore
{
	/** Per label: true objects with an instance of their label within the
	 * match distance, and instances near no true object of their label. */
	struct Objects
	{
		int truth = 0, found = 0, instances = 0, spurious = 0;
	};
	std::map<Label, Objects> objects;
	/** Observed cells: occupied ones, and those within two cells (10 cm at
	 * 5 cm) of a truly occupied cell; free ones, and those truly free. */
	std::size_t occupied = 0, occupiedRight = 0, free = 0, freeRight = 0;
	/** Area the map observed (free or occupied cells), m^2. */
	double knownArea = 0;
	/** Truly occupied cells, and those with an occupied map cell within
	 * two cells (the obstacles the map holds). */
	std::size_t trueOccupied = 0, trueOccupiedMapped = 0;

	double occupiedPrecision() const
	{
		return occupied ? double(occupiedRight) / occupied : 0.0;
	}
	double freePrecision() const
	{
		return free ? double(freeRight) / free : 0.0;
	}
	double obstacleRecall() const
	{
		return trueOccupied ? double(trueOccupiedMapped) / trueOccupied : 0.0;
	}
};

/** Scores `map` against `truth` (SceneMapBuilder::build of the scene) for
 * the instances of `labels`; an instance within `matchM` of a true object
 * of its label finds it. */
inline MapTruthScore scoreAgainstTruth(
    const SemanticMap& map, const SemanticMap& truth,
    const std::vector<Label>& labels, double matchM = 0.5)
{
	MapTruthScore s;
	for (const Label l : labels)
	{
		auto& o = s.objects[l];
		const auto found = map.instances(l);
		const auto real = truth.instances(l);
		o.truth = static_cast<int>(real.size());
		o.instances = static_cast<int>(found.size());
		const auto near = [&](const ObjectInstance& a, const ObjectInstance& b)
		{
			return std::hypot(
			           a.centroid.x - b.centroid.x,
			           a.centroid.y - b.centroid.y) <= matchM;
		};
		for (const auto& t : real)
			for (const auto& f : found)
				if (near(t, f))
				{
					o.found++;
					break;
				}
		for (const auto& f : found)
		{
			bool explained = false;
			for (const auto& t : real) explained = explained || near(t, f);
			o.spurious += !explained;
		}
	}
	using S = SemanticMap::CellState;
	const auto& g = map.geometry();
	// State of `m` two cells around (x, y) at most: any `want` there.
	const auto near = [](const SemanticMap& m, double x, double y, S want)
	{
		const double r = m.geometry().resolution;
		for (int dy = -2; dy <= 2; dy++)
			for (int dx = -2; dx <= 2; dx++)
			{
				int cx, cy;
				if (m.worldToCell(x + dx * r, y + dy * r, cx, cy) &&
				    m.cellState(cx, cy) == want)
					return true;
			}
		return false;
	};
	const auto truthAt = [&](double x, double y)
	{
		int cx, cy;
		if (!truth.worldToCell(x, y, cx, cy))
			return S::Free;  // outside the scene: nothing there
		return truth.cellState(cx, cy);
	};
	for (int cy = 0; cy < g.rows; cy++)
		for (int cx = 0; cx < g.cols; cx++)
		{
			const S st = map.cellState(cx, cy);
			if (st == S::Unknown) continue;
			double x, y;
			map.cellToWorld(cx, cy, x, y);
			if (st == S::Free)
			{
				s.free++;
				s.freeRight += truthAt(x, y) != S::Occupied;
				continue;
			}
			s.occupied++;
			s.occupiedRight += near(truth, x, y, S::Occupied);
		}
	s.knownArea = double(s.free + s.occupied) * g.resolution * g.resolution;
	const auto& tg = truth.geometry();
	for (int cy = 0; cy < tg.rows; cy++)
		for (int cx = 0; cx < tg.cols; cx++)
		{
			if (truth.cellState(cx, cy) != S::Occupied) continue;
			double x, y;
			truth.cellToWorld(cx, cy, x, y);
			s.trueOccupied++;
			s.trueOccupiedMapped += near(map, x, y, S::Occupied);
		}
	return s;
}

}  // namespace semnav::test
