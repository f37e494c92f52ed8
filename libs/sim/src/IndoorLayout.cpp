/* semnav: semantic navigation from tilting-laser sweeps */
#include "IndoorLayout.h"

#include <algorithm>
#include <cmath>

#include "FurniturePlacer.h"
#include "GeneratedWall.h"

namespace semnav::detail
{
namespace
{
using Type = WallOpening::Type;

struct Room
{
	RoomRect rect;
	bool south = true;
	WallOpening entrance;
};

struct Plan
{
	double ceiling = 2.7;
	double tW = 0.2, tE = 0.2, tS = 0.2, tN = 0.2;  // outer walls
	double tCS = 0.1, tCN = 0.1;                    // corridor walls
	double corridorY0 = 0, corridorY1 = 0;          // corridor's wall faces
	double x0 = 0, x1 = 0;                          // inner extent along x
	double width = 0, height = 0;                   // bounds
	std::vector<Room> rooms;
	std::vector<double> partitionsS, partitionsN;  // x of partition walls
	std::vector<double> partitionThickS, partitionThickN;
};

Type randomDoorType(GeneratorRandom& g)
{
	return g.chance(0.3) ? Type::DoubleDoor : Type::Door;
}

/** Room widths along one side, partitions between them. */
std::vector<double> sideWidths(GeneratorRandom& g)
{
	std::vector<double> w(static_cast<std::size_t>(g.uniformInt(2, 3)));
	for (auto& v : w) v = g.uniform(2.8, 5.5);
	return w;
}

Plan makePlan(GeneratorRandom& g)
{
	Plan p;
	p.ceiling = g.uniform(2.5, 3.2);
	p.tW = g.uniform(0.15, 0.35), p.tE = g.uniform(0.15, 0.35);
	p.tS = g.uniform(0.15, 0.35), p.tN = g.uniform(0.15, 0.35);
	p.tCS = g.uniform(0.08, 0.25), p.tCN = g.uniform(0.08, 0.25);
	const double cw = g.uniform(1.5, 2.6);
	const double dS = g.uniform(3.0, 5.0), dN = g.uniform(3.0, 5.0);
	auto wS = sideWidths(g), wN = sideWidths(g);
	std::vector<double> tpS(wS.size() - 1), tpN(wN.size() - 1);
	for (auto& t : tpS) t = g.uniform(0.08, 0.2);
	for (auto& t : tpN) t = g.uniform(0.08, 0.2);
	auto total = [](const std::vector<double>& w, const std::vector<double>& t)
	{
		double s = 0;
		for (double v : w) s += v;
		for (double v : t) s += v;
		return s;
	};
	const double L = std::max(total(wS, tpS), total(wN, tpN));
	wS.back() += L - total(wS, tpS);
	wN.back() += L - total(wN, tpN);
	p.x0 = p.tW, p.x1 = p.tW + L;
	p.width = p.x1 + p.tE;
	const double sy0 = p.tS, sy1 = sy0 + dS;
	p.corridorY0 = sy1 + p.tCS, p.corridorY1 = p.corridorY0 + cw;
	const double ny0 = p.corridorY1 + p.tCN, ny1 = ny0 + dN;
	p.height = ny1 + p.tN;

	auto addSide = [&](const std::vector<double>& w,
	                   const std::vector<double>& tp, bool south,
	                   std::vector<double>& parts, std::vector<double>& thick)
	{
		double x = p.x0;
		for (std::size_t i = 0; i < w.size(); i++)
		{
			Room r;
			r.south = south;
			r.rect = south ? RoomRect{x, sy0, x + w[i], sy1}
			               : RoomRect{x, ny0, x + w[i], ny1};
			x += w[i];
			if (i + 1 < w.size())
			{
				parts.push_back(x + tp[i] / 2);
				thick.push_back(tp[i]);
				x += tp[i];
			}
			p.rooms.push_back(r);
		}
	};
	addSide(wS, tpS, true, p.partitionsS, p.partitionThickS);
	addSide(wN, tpN, false, p.partitionsN, p.partitionThickN);
	return p;
}

/** Entrances: about 40 % open gaps, at least two. */
void chooseEntrances(GeneratorRandom& g, Plan& p)
{
	int gaps = 0;
	for (auto& r : p.rooms)
	{
		const double t = r.south ? p.tCS : p.tCN;
		Type type = g.chance(0.4) ? Type::Gap : randomDoorType(g);
		r.entrance = WallOpening::random(g, type, t, 2.15);
		gaps += type == Type::Gap;
	}
	for (std::size_t i = 0; gaps < 2 && i < p.rooms.size(); i += 2)
		if (p.rooms[i].entrance.type != Type::Gap)
		{
			p.rooms[i].entrance = WallOpening::random(g, Type::Gap, 0.1, 2.15);
			gaps++;
		}
	for (auto& r : p.rooms)
	{
		const double half = r.entrance.width / 2 + 0.3;
		r.entrance.center = g.uniform(r.rect.x0 + half, r.rect.x1 - half);
	}
}

void addWalls(SceneDraft& d, GeneratorRandom& g, const Plan& p)
{
	const double h = p.ceiling;
	// Outer walls; the west and east ones may have a door onto the corridor.
	GeneratedWall s{true, p.tS / 2, 0, p.width, p.tS, h, 1, {}};
	GeneratedWall n{true, p.height - p.tN / 2, 0, p.width, p.tN, h, -1, {}};
	GeneratedWall w{false, p.tW / 2, p.tS, p.height - p.tN, p.tW, h, 1, {}};
	GeneratedWall e{
	    false, p.width - p.tE / 2, p.tS, p.height - p.tN, p.tE, h, -1, {}};
	const double cy = 0.5 * (p.corridorY0 + p.corridorY1);
	for (GeneratedWall* end : {&w, &e})
		if (g.chance(0.5))
		{
			auto o =
			    WallOpening::random(g, randomDoorType(g), end->thickness, 2.15);
			const double room = p.corridorY1 - p.corridorY0 - o.width;
			if (room < 0.1) continue;
			o.center = cy + g.uniform(-room / 2, room / 2);
			end->openings.push_back(o);
		}
	for (const auto* wall : {&s, &n, &w, &e}) wall->addTo(d);

	// Corridor walls with the rooms' entrances.
	GeneratedWall cs{true, p.corridorY0 - p.tCS / 2, p.x0, p.x1, p.tCS, h, 1,
	                 {}};
	GeneratedWall cn{true, p.corridorY1 + p.tCN / 2, p.x0, p.x1, p.tCN, h, -1,
	                 {}};
	for (const auto& r : p.rooms)
		(r.south ? cs : cn).openings.push_back(r.entrance);
	cs.addTo(d);
	cn.addTo(d);

	// Partitions between rooms, a third of them with a closed door.
	auto partitions = [&](const std::vector<double>& xs,
	                      const std::vector<double>& ts, double y0, double y1)
	{
		for (std::size_t i = 0; i < xs.size(); i++)
		{
			GeneratedWall pw{
			    false, xs[i], y0, y1, ts[i], h, g.chance(0.5) ? 1 : -1, {}};
			if (g.chance(0.33))
			{
				auto o = WallOpening::random(g, Type::Door, ts[i], 2.15);
				const double room = (y1 - y0) - o.width - 0.6;
				if (room > 0)
				{
					o.center = 0.5 * (y0 + y1) + g.uniform(-room / 2, room / 2);
					pw.openings.push_back(o);
				}
			}
			pw.addTo(d);
		}
	};
	partitions(p.partitionsS, p.partitionThickS, p.tS, p.corridorY0 - p.tCS);
	partitions(
	    p.partitionsN, p.partitionThickN, p.corridorY1 + p.tCN,
	    p.height - p.tN);
}

/** Where the robot stops inside a room with an open gap. */
mrpt::math::TPoint2D roomStop(const Room& r)
{
	const double y = r.south ? r.rect.y1 - 0.45 * r.rect.depth()
	                         : r.rect.y0 + 0.45 * r.rect.depth();
	return {r.entrance.center, y};
}

void addKeepOuts(SceneDraft& d, const Plan& p)
{
	const double cy = 0.5 * (p.corridorY0 + p.corridorY1);
	d.addKeepOut({p.x0, cy}, {p.x1, cy}, 0.55);
	for (const auto& r : p.rooms)
	{
		const double x = r.entrance.center;
		const double wallY = r.south ? p.corridorY0 : p.corridorY1;
		const double in = r.south ? -1 : 1;
		// In front of the opening, both sides.
		d.addKeepOut(
		    {x, wallY - in * 0.9}, {x, wallY + in * 1.0},
		    r.entrance.width / 2 + 0.15);
		if (r.entrance.isDoor()) continue;
		const auto stop = roomStop(r);
		d.addKeepOut({x, wallY}, stop, 0.6);
		d.addKeepOut(stop, stop, 0.9);
	}
}

void furnish(SceneDraft& d, const Plan& p)
{
	auto& g = d.rng();
	FurniturePlacer f(d);
	// Stairs in one of the rooms the robot enters (an open gap), climbing
	// toward its outer wall.
	std::vector<const Room*> open;
	for (const auto& r : p.rooms)
		if (!r.entrance.isDoor()) open.push_back(&r);
	if (g.chance(0.85) && !open.empty())
	{
		const Room* r = open[static_cast<std::size_t>(
		    g.uniformInt(0, static_cast<int>(open.size()) - 1))];
		f.stairs(r->rect, r->south ? 0 : 1);
	}
	for (const auto& r : p.rooms)
	{
		if (g.chance(0.6)) f.washbasin(r.rect);
		for (int k = g.uniformInt(1, 2); k > 0; k--)
			f.wastebasket(r.rect, g.uniformInt(0, 2));
		for (int k = g.uniformInt(0, 2); k > 0; k--) f.cabinet(r.rect);
		if (g.chance(0.6)) f.tableWithChairs(r.rect, g.uniformInt(0, 3));
		for (int k = g.uniformInt(0, 3); k > 0; k--) f.clutter(r.rect);
	}
	// Corridor: a washbasin, wastebaskets and clutter where it is wide.
	const RoomRect corridor{p.x0, p.corridorY0, p.x1, p.corridorY1};
	if (g.chance(0.3)) f.washbasin(corridor);
	for (int k = g.uniformInt(0, 2); k > 0; k--) f.wastebasket(corridor, 0);
	for (int k = g.uniformInt(0, 2); k > 0; k--) f.clutter(corridor);
}

void addTrajectory(SceneDraft& d, const Plan& p)
{
	auto& g = d.rng();
	const double cy = 0.5 * (p.corridorY0 + p.corridorY1);
	std::vector<const Room*> open;
	for (const auto& r : p.rooms)
		if (!r.entrance.isDoor()) open.push_back(&r);
	std::sort(
	    open.begin(), open.end(),
	    [](const Room* a, const Room* b)
	    { return a->entrance.center < b->entrance.center; });
	double x = p.x0 + g.uniform(0.7, 1.2);
	const double xEnd = p.x1 - g.uniform(0.7, 1.2);
	auto walkTo = [&](double target)
	{
		while (target - x > 2.6)
		{
			x += g.uniform(1.6, 2.4);
			d.addPose(x, cy, g.uniform(-50, 50));
		}
	};
	d.addPose(x, cy, g.uniform(-25, 25));
	for (const Room* r : open)
	{
		const double xo = r->entrance.center;
		if (xo < x + 0.3) continue;
		walkTo(xo);
		const double in = r->south ? -90 : 90;
		x = xo;
		d.addPose(x, cy, in + g.uniform(-15, 15));
		const auto stop = roomStop(*r);
		d.addPose(stop.x, stop.y, in + g.uniform(-30, 30));
		const int turn = g.chance(0.5) ? 1 : -1;
		d.addPose(stop.x, stop.y, in + turn * g.uniform(70, 110));
		d.addPose(x, cy, g.uniform(-30, 30));
	}
	walkTo(xEnd);
	x = xEnd;
	d.addPose(x, cy, g.uniform(-30, 30));
	d.addPose(x, cy, 180 + g.uniform(-30, 30));
}

}  // namespace

void IndoorLayout::build(SceneDraft& d)
{
	auto& g = d.rng();
	Plan p = makePlan(g);
	chooseEntrances(g, p);
	d.setBounds(0, 0, p.width, p.height);
	d.setCeiling(p.ceiling);
	d.setOdometryBias(g.uniform(0, 3.5));
	d.addComment(
	    "corridor x " + formatNumber(p.x0) + ".." + formatNumber(p.x1) +
	    ", y " + formatNumber(p.corridorY0) + ".." +
	    formatNumber(p.corridorY1) + "; ceiling " + formatNumber(p.ceiling) +
	    " m");
	for (const auto& r : p.rooms)
		d.addComment(
		    std::string(r.south ? "south" : "north") + " room x " +
		    formatNumber(r.rect.x0) + ".." + formatNumber(r.rect.x1) + ": " +
		    r.entrance.describe());
	addWalls(d, g, p);
	addKeepOuts(d, p);
	furnish(d, p);
	addTrajectory(d, p);
}

}  // namespace semnav::detail
