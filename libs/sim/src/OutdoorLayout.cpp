/* semnav: semantic navigation from tilting-laser sweeps */
#include "OutdoorLayout.h"

#include <algorithm>
#include <cmath>

#include "GeneratedWall.h"

namespace semnav::detail
{
namespace
{
using mrpt::math::TPoint2D;
using Type = WallOpening::Type;
constexpr double kDeg = M_PI / 180;

/** The sidewalk: centre line y(x) and width w(x), both smooth. */
struct Sidewalk
{
	double y0 = 0, amp = 0, period = 30, phase = 0;
	double w0 = 2, dw = 0, wperiod = 20, wphase = 0;
	double center(double x) const
	{
		return y0 + amp * std::sin(2 * M_PI * x / period + phase);
	}
	double width(double x) const
	{
		return w0 + dw * std::sin(2 * M_PI * x / wperiod + wphase);
	}
	double lower(double x) const { return center(x) - width(x) / 2; }
	double upper(double x) const { return center(x) + width(x) / 2; }
	double headingDeg(double x) const
	{
		const double dy =
		    amp * 2 * M_PI / period * std::cos(2 * M_PI * x / period + phase);
		return std::atan(dy) / kDeg;
	}
};

struct Branch
{
	double x0, x1;  // a straight path from the sidewalk north to a door
	double doorX;
};

struct Plan
{
	double width = 30, height = 20, facadeY = 16;
	Sidewalk walk;
	std::vector<Branch> branches;
	double grassRough = 0.025, walkRough = 0.003;
};

/** x samples every ~0.5 m with the branch edges included exactly. */
std::vector<double> samples(double a, double b)
{
	std::vector<double> xs;
	const int n = std::max(1, static_cast<int>(std::ceil((b - a) / 0.5)));
	for (int i = 0; i <= n; i++) xs.push_back(a + (b - a) * i / n);
	return xs;
}

void addGround(SceneDraft& d, const Plan& p)
{
	const auto& s = p.walk;
	const double W = p.width, H = p.height;
	const auto all = samples(0, W);
	Polygon2D below{{0, 0}, {W, 0}}, walk;
	for (auto it = all.rbegin(); it != all.rend(); ++it)
		below.emplace_back(*it, s.lower(*it));
	for (double x : all) walk.emplace_back(x, s.upper(x));
	for (auto it = all.rbegin(); it != all.rend(); ++it)
		walk.emplace_back(*it, s.lower(*it));
	d.addTerrain(Label::Grass, below, p.grassRough);
	d.addTerrain(Label::Sidewalk, walk, p.walkRough);
	// North of the sidewalk: grass pieces between the branch paths.
	double start = 0;
	auto grassPiece = [&](double a, double b)
	{
		if (b - a < 0.05) return;
		Polygon2D poly;
		for (double x : samples(a, b)) poly.emplace_back(x, s.upper(x));
		poly.emplace_back(b, H);
		poly.emplace_back(a, H);
		d.addTerrain(Label::Grass, poly, p.grassRough);
	};
	for (const auto& b : p.branches)
	{
		grassPiece(start, b.x0);
		Polygon2D path;
		for (double x : samples(b.x0, b.x1)) path.emplace_back(x, s.upper(x));
		path.emplace_back(b.x1, H);
		path.emplace_back(b.x0, H);
		d.addTerrain(Label::Sidewalk, path, p.walkRough);
		start = b.x1;
	}
	grassPiece(start, W);
}

/** Buildings along the north edge; returns the doors' x. */
std::vector<double> addBuildings(SceneDraft& d, GeneratorRandom& g, Plan& p)
{
	std::vector<std::pair<double, double>> spans;
	if (g.chance(0.5))
		spans.push_back({g.uniform(1, 4), p.width - g.uniform(1, 4)});
	else
	{
		const double mid = p.width * g.uniform(0.4, 0.6), gap = g.uniform(3, 6);
		spans.push_back({g.uniform(0.5, 3), mid - gap / 2});
		spans.push_back({mid + gap / 2, p.width - g.uniform(0.5, 3)});
	}
	std::vector<double> doors;
	for (const auto& [a, b] : spans)
	{
		const double t = g.uniform(0.25, 0.45), h = g.uniform(3, 6);
		GeneratedWall facade{true, p.facadeY + t / 2, a, b, t, h, -1, {}};
		const int n = g.uniformInt(1, 2);
		for (int k = 0; k < n; k++)
		{
			auto o = WallOpening::random(
			    g, g.chance(0.35) ? Type::DoubleDoor : Type::Door, t, 2.4);
			const double lo = a + (b - a) * k / n + o.width / 2 + 0.5;
			const double hi = a + (b - a) * (k + 1) / n - o.width / 2 - 0.5;
			if (hi < lo) continue;
			o.center = g.uniform(lo, hi);
			facade.openings.push_back(o);
			doors.push_back(o.center);
			d.addComment(
			    "building x " + formatNumber(a) + ".." + formatNumber(b) +
			    ": " + o.describe() + " at x " + formatNumber(o.center));
		}
		facade.addTo(d);
		for (const double x : {a + t / 2, b - t / 2})
			d.add(
			    Label::Wall,
			    {DraftPart::box(
			        x, 0.5 * (p.facadeY + p.height), h / 2, t,
			        p.height - p.facadeY, h)},
			    true);
	}
	return doors;
}

void addKeepOuts(SceneDraft& d, const Plan& p)
{
	const auto xs = samples(0, p.width);
	for (std::size_t i = 1; i < xs.size(); i++)
	{
		const double a = xs[i - 1], b = xs[i];
		d.addKeepOut(
		    {a, p.walk.center(a)}, {b, p.walk.center(b)},
		    0.5 * std::max(p.walk.width(a), p.walk.width(b)) + 0.25);
	}
	for (const auto& br : p.branches)
	{
		const double x = 0.5 * (br.x0 + br.x1);
		d.addKeepOut(
		    {x, p.walk.center(x)}, {x, p.facadeY},
		    0.5 * (br.x1 - br.x0) + 0.25);
	}
}

/** A point `off` metres beyond the sidewalk's edge at x (side +1 north). */
TPoint2D besideWalk(const Plan& p, double x, int side, double off)
{
	return {x, side > 0 ? p.walk.upper(x) + off : p.walk.lower(x) - off};
}

void addBench(SceneDraft& d, GeneratorRandom& g, const Plan& p)
{
	const double L = g.uniform(1.2, 1.8), D = g.uniform(0.4, 0.5);
	for (int k = 0; k < 40; k++)
	{
		const int side = g.chance(0.5) ? 1 : -1;
		const double x = g.uniform(2, p.width - 2);
		const auto c = besideWalk(p, x, side, g.uniform(0.5, 0.9) + D / 2);
		// Facing the sidewalk: local +x toward it.
		const double yaw = (side > 0 ? -90 : 90) + p.walk.headingDeg(x);
		const double cy = std::cos(yaw * kDeg), sy = std::sin(yaw * kDeg);
		auto at = [&](double lx, double ly)
		{ return TPoint2D(c.x + cy * lx - sy * ly, c.y + sy * lx + cy * ly); };
		const auto back = at(-D / 2 + 0.03, 0);
		std::vector<DraftPart> parts{
		    DraftPart::box(c.x, c.y, 0.44, D, L, 0.05, yaw),
		    DraftPart::box(back.x, back.y, 0.72, 0.05, L, 0.4, yaw)};
		for (const int s : {-1, 1})
		{
			const auto e = at(0, s * (L / 2 - 0.1));
			parts.push_back(DraftPart::box(e.x, e.y, 0.21, D, 0.06, 0.42, yaw));
		}
		if (!d.isFree(parts, 0.1)) continue;
		d.add(Label::Obstacle, parts);
		return;
	}
}

/** A vertical cylinder (post or bin) `off` beyond a sidewalk edge. */
struct RoadsideCylinder
{
	double rMin, rMax, hMin, hMax, offMin, offMax;
	bool offFromRim;  ///< `off` from the cylinder's rim, not its axis
};

template <typename TryAdd>
void addRoadsideCylinder(
    GeneratorRandom& g, const Plan& p, Label l, const RoadsideCylinder& c,
    TryAdd tryAdd)
{
	const double r = g.uniform(c.rMin, c.rMax), h = g.uniform(c.hMin, c.hMax);
	tryAdd(
	    l,
	    [&]
	    {
		    // One draw per statement: argument order is unspecified.
		    const double x = g.uniform(1, p.width - 1);
		    const int side = g.chance(0.5) ? 1 : -1;
		    const double off =
		        g.uniform(c.offMin, c.offMax) + (c.offFromRim ? r : 0);
		    const auto at = besideWalk(p, x, side, off);
		    return std::vector<DraftPart>{
		        DraftPart::cylinder(at.x, at.y, h / 2, r, h)};
	    });
}

void addStreetFurniture(SceneDraft& d, GeneratorRandom& g, const Plan& p)
{
	auto tryAdd = [&](Label l, auto make)
	{
		for (int k = 0; k < 40; k++)
			if (const auto parts = make(); d.isFree(parts, 0.1))
				return d.add(l, parts);
	};
	const RoadsideCylinder post{0.04, 0.08, 0.8, 1.2, 0.3, 0.7, false};
	const RoadsideCylinder bin{0.13, 0.2, 0.32, 0.55, 0.3, 0.6, true};
	for (int n = g.uniformInt(3, 8); n > 0; n--)
		addRoadsideCylinder(g, p, Label::Obstacle, post, tryAdd);
	for (int n = g.uniformInt(1, 2); n > 0; n--) addBench(d, g, p);
	for (int n = g.uniformInt(1, 3); n > 0; n--)
		addRoadsideCylinder(g, p, Label::Wastebasket, bin, tryAdd);
	// Low walls on the grass, along the sidewalk: obstacles (a robot sees
	// over them; no room or building wall, docs/generated-scenes.md).
	for (int n = g.uniformInt(0, 2); n > 0; n--)
	{
		const double L = g.uniform(2, 5), t = g.uniform(0.15, 0.3);
		const double h = g.uniform(0.4, 0.9);
		tryAdd(
		    Label::Obstacle,
		    [&]
		    {
			    const double x = g.uniform(L / 2 + 0.5, p.width - L / 2 - 0.5);
			    const int side = g.chance(0.5) ? 1 : -1;
			    const auto c = besideWalk(p, x, side, g.uniform(1.5, 3.0));
			    return std::vector<DraftPart>{DraftPart::box(
			        c.x, c.y, h / 2, L, t, h, p.walk.headingDeg(x))};
		    });
	}
}

void addTrajectory(SceneDraft& d, GeneratorRandom& g, const Plan& p)
{
	const auto& s = p.walk;
	double x = g.uniform(1.5, 2.5);
	const double xEnd = p.width - g.uniform(1.5, 2.5);
	auto stop = [&](double at, double turn)
	{ d.addPose(at, s.center(at), s.headingDeg(at) + turn); };
	stop(x, g.uniform(-20, 20));
	for (const auto& b : p.branches)
	{
		const double bx = 0.5 * (b.x0 + b.x1);
		if (bx < x + 0.5) continue;
		while (bx - x > 3.2)
		{
			x += g.uniform(2.0, 3.0);
			stop(x, g.uniform(-35, 35));
		}
		x = bx;
		stop(x, 90 - s.headingDeg(x) + g.uniform(-20, 20));
		const double y0 = s.upper(x), y1 = p.facadeY - g.uniform(1.2, 1.8);
		if (y1 - y0 > 1.5)
			d.addPose(x, 0.5 * (y0 + y1), 90 + g.uniform(-15, 15));
		d.addPose(x, y1, 90 + g.uniform(-15, 15));
		stop(x, g.uniform(-30, 30));
	}
	while (xEnd - x > 3.2)
	{
		x += g.uniform(2.0, 3.0);
		stop(x, g.uniform(-35, 35));
	}
	stop(xEnd, 180 + g.uniform(-30, 30));
}

}  // namespace

void OutdoorLayout::build(SceneDraft& d)
{
	auto& g = d.rng();
	Plan p;
	p.width = g.uniform(24, 34), p.height = g.uniform(16, 22);
	p.facadeY = p.height - g.uniform(3, 5);
	auto& s = p.walk;
	s.w0 = g.uniform(1.6, 3.0), s.dw = g.uniform(0, 0.4);
	s.wperiod = g.uniform(10, 30), s.wphase = g.uniform(0, 2 * M_PI);
	s.amp = g.chance(0.3) ? 0.0 : g.uniform(0.3, 1.8);
	s.period = g.uniform(18, 40), s.phase = g.uniform(0, 2 * M_PI);
	s.y0 = g.uniform(0.35, 0.55) * p.facadeY;
	p.grassRough = g.uniform(0.015, 0.035);
	p.walkRough = g.uniform(0.002, 0.004);
	d.setBounds(0, 0, p.width, p.height);
	d.setOdometryBias(g.uniform(0, 2));
	d.addComment(
	    "sidewalk around y " + formatNumber(s.y0) + ", " + formatNumber(s.w0) +
	    " m wide, bends " + formatNumber(s.amp) + " m; facade y " +
	    formatNumber(p.facadeY));
	const auto doors = addBuildings(d, g, p);
	double lastEnd = 0;
	for (const double x : doors)
	{
		const double w = g.uniform(1.2, 2.0);
		Branch b{x - w / 2, x + w / 2, x};
		if (g.chance(0.75) && b.x0 > lastEnd + 1.0 && b.x1 < p.width - 1)
		{
			p.branches.push_back(b);
			lastEnd = b.x1;
		}
	}
	addGround(d, p);
	addKeepOuts(d, p);
	addStreetFurniture(d, g, p);
	addTrajectory(d, g, p);
}

}  // namespace semnav::detail
