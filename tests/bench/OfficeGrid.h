/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once
// The generated office grid of bench_planner: square rooms with doors and
// boxes, its C-space u, a start and a goal.
#include <semnav/planning/CellOccupancy.h>
#include <semnav/planning/GoalLayer.h>
#include <semnav/planning/TraversabilityBuilder.h>
#include <semnav/planning/TraversabilityGrid.h>

#include <algorithm>
#include <functional>
#include <memory>
#include <numeric>
#include <random>
#include <vector>

namespace semnav::test
{
struct OfficeMap
{
	GridGeometry geometry;
	std::vector<CellOccupancy> occupancy;
	TraversabilityGrid u;
	GoalLayer goals;
	CellIndex start, goal;
	std::size_t boxes = 0;
};

/** Square office of `rooms` x `rooms` rooms of `room` cells, 10 cm walls,
 * 1 m doors (a random spanning tree of the rooms plus extra doors), boxes
 * of 0.3-1.5 m kept 1.2 m away from doors, start and goal. */
inline std::unique_ptr<OfficeMap> makeOffice(int rooms, int room, int nBoxes)
{
	auto m = std::make_unique<OfficeMap>();
	const int n = rooms * room;
	m->geometry = GridGeometry(0.05, 0, 0, n, n);
	const auto& g = m->geometry;
	m->occupancy.assign(g.cellCount(), CellOccupancy::Free);
	const auto fill = [&](int r0, int c0, int r1, int c1)
	{
		for (int r = std::max(0, r0); r < std::min(n, r1); r++)
			for (int c = std::max(0, c0); c < std::min(n, c1); c++)
				m->occupancy[g.index(r, c)] = CellOccupancy::Occupied;
	};
	const auto clear = [&](int r0, int c0, int r1, int c1)
	{
		for (int r = std::max(0, r0); r < std::min(n, r1); r++)
			for (int c = std::max(0, c0); c < std::min(n, c1); c++)
				m->occupancy[g.index(r, c)] = CellOccupancy::Free;
	};
	const int wall = 2, door = 20;
	fill(0, 0, wall, n);
	fill(n - wall, 0, n, n);
	fill(0, 0, n, wall);
	fill(0, n - wall, n, n);
	for (int k = 1; k < rooms; k++)
	{
		fill(k * room - 1, 0, k * room + 1, n);
		fill(0, k * room - 1, n, k * room + 1);
	}

	std::mt19937_64 rng(20240607);
	// Doors: Kruskal spanning tree over the rooms, plus 30 % extra doors.
	struct Edge
	{
		int a, b;
	};
	std::vector<Edge> edges;
	for (int i = 0; i < rooms; i++)
		for (int j = 0; j < rooms; j++)
		{
			if (j + 1 < rooms)
				edges.push_back({i * rooms + j, i * rooms + j + 1});
			if (i + 1 < rooms)
				edges.push_back({i * rooms + j, (i + 1) * rooms + j});
		}
	std::shuffle(edges.begin(), edges.end(), rng);
	std::vector<int> parent(rooms * rooms);
	std::iota(parent.begin(), parent.end(), 0);
	std::function<int(int)> root = [&](int a)
	{ return parent[a] == a ? a : parent[a] = root(parent[a]); };
	std::uniform_real_distribution<double> U(0, 1);
	std::vector<std::pair<int, int>> doorCentres;
	for (const auto& e : edges)
	{
		const bool tree = root(e.a) != root(e.b);
		if (!tree && U(rng) > 0.3) continue;
		parent[root(e.a)] = root(e.b);
		const int ia = e.a / rooms, ja = e.a % rooms;
		const int off = 10 + static_cast<int>(U(rng) * (room - door - 20));
		if (e.b == e.a + 1)  // vertical wall at column (ja + 1) * room
		{
			const int c = (ja + 1) * room, r = ia * room + off;
			clear(r, c - 1, r + door, c + 1);
			doorCentres.push_back({r + door / 2, c});
		}
		else
		{
			const int r = (ia + 1) * room, c = ja * room + off;
			clear(r - 1, c, r + 1, c + door);
			doorCentres.push_back({r, c + door / 2});
		}
	}

	m->start = {room / 2, room / 2};
	m->goal = {n - room / 2, n - room / 2};
	const auto near = [](int r0, int c0, int r1, int c1, int pr, int pc, int d)
	{ return pr >= r0 - d && pr < r1 + d && pc >= c0 - d && pc < c1 + d; };
	for (int attempt = 0;
	     attempt < 100 * nBoxes && m->boxes < static_cast<std::size_t>(nBoxes);
	     attempt++)
	{
		const int h = 6 + static_cast<int>(U(rng) * 24);
		const int w = 6 + static_cast<int>(U(rng) * 24);
		const int r0 = static_cast<int>(U(rng) * (n - h));
		const int c0 = static_cast<int>(U(rng) * (n - w));
		bool ok =
		    !near(r0, c0, r0 + h, c0 + w, m->start.row, m->start.col, 30) &&
		    !near(r0, c0, r0 + h, c0 + w, m->goal.row, m->goal.col, 30);
		for (const auto& [dr, dc] : doorCentres)
			ok = ok && !near(r0, c0, r0 + h, c0 + w, dr, dc, 24);
		if (!ok) continue;
		fill(r0, c0, r0 + h, c0 + w);
		m->boxes++;
	}

	TraversabilityBuilder::TOptions o;
	o.robotRadius = 0.2;
	m->u = TraversabilityBuilder(o).build(
	    g, {}, m->occupancy, CostProfile::Shortest);
	m->goals = GoalLayer(g);
	m->goals.addCell(m->goal);
	return m;
}

}  // namespace semnav::test
