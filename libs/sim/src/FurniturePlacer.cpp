/* semnav: semantic navigation from tilting-laser sweeps */
#include "FurniturePlacer.h"

#include <algorithm>
#include <cmath>

namespace semnav::detail
{
namespace
{
constexpr double kDeg = M_PI / 180;
/** Gap kept between generated objects. */
constexpr double kMargin = 0.05;
/** Kept between furniture and the wall it stands against. */
constexpr double kWallGap = 0.002;

/** (x, y) + local (lx, ly) turned by yawDeg. */
mrpt::math::TPoint2D local(
    double x, double y, double yawDeg, double lx, double ly)
{
	const double c = std::cos(yawDeg * kDeg), s = std::sin(yawDeg * kDeg);
	return {x + c * lx - s * ly, y + s * lx + c * ly};
}
}  // namespace

FurniturePlacer::Spot FurniturePlacer::wallSpot(
    const RoomRect& r, double depth, double width, double gap)
{
	auto& g = m_draft.rng();
	const int side = g.uniformInt(0, 3);
	const double off = depth / 2 + gap + kWallGap;
	if (side < 2)
	{
		const double x = g.uniform(r.x0 + width / 2, r.x1 - width / 2);
		return side == 0 ? Spot{x, r.y0 + off, 90} : Spot{x, r.y1 - off, -90};
	}
	const double y = g.uniform(r.y0 + width / 2, r.y1 - width / 2);
	return side == 2 ? Spot{r.x0 + off, y, 0} : Spot{r.x1 - off, y, 180};
}

bool FurniturePlacer::place(
    Label label, const std::function<std::vector<DraftPart>()>& candidate)
{
	for (int k = 0; k < 40; k++)
	{
		const auto parts = candidate();
		if (parts.empty() || !m_draft.isFree(parts, kMargin)) continue;
		m_draft.add(label, parts);
		return true;
	}
	return false;
}

bool FurniturePlacer::washbasin(const RoomRect& r)
{
	auto& g = m_draft.rng();
	const double w = g.uniform(0.40, 0.62), d = g.uniform(0.35, 0.50);
	const double t = g.uniform(0.12, 0.19), top = g.uniform(0.78, 0.92);
	const double pr = g.uniform(0.06, 0.10);
	const double back = d / 2 - pr - g.uniform(0.02, 0.10);
	return place(
	    Label::Washbasin,
	    [&]
	    {
		    const Spot s = wallSpot(r, d, w, 0.0);
		    const auto p = local(s.x, s.y, s.yawDeg, -back, 0);
		    return std::vector<DraftPart>{
		        DraftPart::box(s.x, s.y, top - t / 2, d, w, t, s.yawDeg),
		        DraftPart::cylinder(p.x, p.y, (top - t) / 2, pr, top - t)};
	    });
}

bool FurniturePlacer::wastebasket(const RoomRect& r, int where)
{
	auto& g = m_draft.rng();
	const double rad = g.uniform(0.12, 0.20), h = g.uniform(0.30, 0.50);
	return place(
	    Label::Wastebasket,
	    [&]
	    {
		    double x = 0, y = 0;
		    if (where == 0)
		    {
			    const Spot s =
			        wallSpot(r, 2 * rad, 2 * rad, g.uniform(0, 0.08));
			    x = s.x, y = s.y;
		    }
		    else if (where == 1)
		    {
			    const double e = rad + 0.02 + kWallGap;
			    x = g.chance(0.5) ? r.x0 + e : r.x1 - e;
			    y = g.chance(0.5) ? r.y0 + e : r.y1 - e;
		    }
		    else
		    {
			    x = g.uniform(r.x0 + 0.6, r.x1 - 0.6);
			    y = g.uniform(r.y0 + 0.6, r.y1 - 0.6);
		    }
		    return std::vector<DraftPart>{
		        DraftPart::cylinder(x, y, h / 2, rad, h)};
	    });
}

bool FurniturePlacer::cabinet(const RoomRect& r)
{
	auto& g = m_draft.rng();
	const double d = g.uniform(0.35, 0.6), w = g.uniform(0.5, 1.3);
	const double h = g.uniform(0.7, 1.9);
	return place(
	    Label::Obstacle,
	    [&]
	    {
		    const Spot s = wallSpot(r, d, w, g.uniform(0, 0.03));
		    return std::vector<DraftPart>{
		        DraftPart::box(s.x, s.y, h / 2, d, w, h, s.yawDeg)};
	    });
}

bool FurniturePlacer::clutter(const RoomRect& r)
{
	auto& g = m_draft.rng();
	if (g.chance(0.3)) return plantPot(r);
	const double a = g.uniform(0.2, 0.45), b = g.uniform(0.2, 0.45);
	const double h = g.uniform(0.2, 0.6);
	const double turn = g.uniform(-20, 20);
	return place(
	    Label::Obstacle,
	    [&]
	    {
		    const Spot s = wallSpot(r, a, b, g.uniform(0.02, 0.15));
		    return std::vector<DraftPart>{
		        DraftPart::box(s.x, s.y, h / 2, a, b, h, s.yawDeg + turn)};
	    });
}

bool FurniturePlacer::plantPot(const RoomRect& r)
{
	// The pot is a wastebasket's size; the plant in it is what tells them
	// apart: foliage wider than the pot above it, on a short stem when
	// `stem` > 0 (docs/generated-scenes.md).
	auto& g = m_draft.rng();
	const double pr = g.uniform(0.10, 0.22), ph = g.uniform(0.25, 0.55);
	const double fr = pr * g.uniform(1.5, 2.5), fh = g.uniform(0.3, 0.8);
	const double stem = g.chance(0.5) ? g.uniform(0.05, 0.25) : 0.0;
	const double f0 = ph + stem;
	return place(
	    Label::Obstacle,
	    [&]
	    {
		    const Spot s = wallSpot(r, 2 * fr, 2 * fr, g.uniform(0.02, 0.10));
		    std::vector<DraftPart> parts{
		        DraftPart::cylinder(s.x, s.y, ph / 2, pr, ph),
		        DraftPart::cylinder(s.x, s.y, f0 + fh / 2, fr, fh)};
		    if (stem > 0)
			    parts.push_back(
			        DraftPart::cylinder(s.x, s.y, ph + stem / 2, 0.025, stem));
		    return parts;
	    });
}

std::vector<DraftPart> FurniturePlacer::chair(double x, double y, double yawDeg)
{
	// Seat 0.44 m square at 0.45 m, backrest behind, four legs; the chair
	// faces +x of its frame.
	std::vector<DraftPart> parts{
	    DraftPart::box(x, y, 0.45, 0.44, 0.44, 0.05, yawDeg)};
	const auto back = local(x, y, yawDeg, -0.2, 0);
	parts.push_back(
	    DraftPart::box(back.x, back.y, 0.7, 0.04, 0.44, 0.45, yawDeg));
	for (const int sx : {-1, 1})
		for (const int sy : {-1, 1})
		{
			const auto p = local(x, y, yawDeg, sx * 0.19, sy * 0.19);
			parts.push_back(
			    DraftPart::box(p.x, p.y, 0.21, 0.035, 0.035, 0.42, yawDeg));
		}
	return parts;
}

bool FurniturePlacer::tableWithChairs(const RoomRect& r, int chairs)
{
	auto& g = m_draft.rng();
	const double w = g.uniform(0.8, 1.6), d = g.uniform(0.6, 0.9);
	const double h = g.uniform(0.70, 0.76);
	if (r.width() < w + 1.6 || r.depth() < w + 1.6) return false;
	double tx = 0, ty = 0, tyaw = 0;
	const bool placed = place(
	    Label::Obstacle,
	    [&]
	    {
		    tx = g.uniform(r.x0 + 0.8 + w / 2, r.x1 - 0.8 - w / 2);
		    ty = g.uniform(r.y0 + 0.8 + w / 2, r.y1 - 0.8 - w / 2);
		    tyaw =
		        g.chance(0.7) ? 90.0 * g.uniformInt(0, 1) : g.uniform(0, 180);
		    std::vector<DraftPart> parts{
		        DraftPart::box(tx, ty, h - 0.025, w, d, 0.05, tyaw)};
		    for (const int sx : {-1, 1})
			    for (const int sy : {-1, 1})
			    {
				    const auto p = local(
				        tx, ty, tyaw, sx * (w / 2 - 0.05), sy * (d / 2 - 0.05));
				    parts.push_back(DraftPart::box(
				        p.x, p.y, (h - 0.05) / 2, 0.05, 0.05, h - 0.05, tyaw));
			    }
		    return parts;
	    });
	if (!placed) return false;
	for (int k = 0; k < chairs; k++)
	{
		// Beside a long side, facing the table, pulled out a little.
		const int side = g.chance(0.5) ? 1 : -1;
		const double along = g.uniform(-w / 2 + 0.25, w / 2 - 0.25);
		const double out = d / 2 + g.uniform(0.15, 0.35);
		const auto p = local(tx, ty, tyaw, along, side * out);
		const double yaw = tyaw - side * 90 + g.uniform(-25, 25);
		const auto parts = chair(p.x, p.y, yaw);
		if (m_draft.isFree(parts, 0.02)) m_draft.add(Label::Obstacle, parts);
	}
	return true;
}

bool FurniturePlacer::stairs(const RoomRect& r, int side)
{
	auto& g = m_draft.rng();
	const int steps = g.uniformInt(3, 7);
	const double rise = g.uniform(0.15, 0.19), run = g.uniform(0.25, 0.32);
	const double width = g.uniform(0.9, 1.6), L = steps * run;
	return place(
	    Label::Stairs,
	    [&]
	    {
		    const bool alongY = side < 2;
		    const double lo = (alongY ? r.x0 : r.y0) + width / 2 + 0.1;
		    const double hi = (alongY ? r.x1 : r.y1) - width / 2 - 0.1;
		    if (hi < lo) return std::vector<DraftPart>{};
		    const double a = g.uniform(lo, hi);
		    switch (side)
		    {
			    case 0:
				    return std::vector<DraftPart>{DraftPart::stairs(
				        a, r.y0 + kWallGap + L, -90, steps, rise, run, width)};
			    case 1:
				    return std::vector<DraftPart>{DraftPart::stairs(
				        a, r.y1 - kWallGap - L, 90, steps, rise, run, width)};
			    case 2:
				    return std::vector<DraftPart>{DraftPart::stairs(
				        r.x0 + kWallGap + L, a, 180, steps, rise, run, width)};
			    default:
				    return std::vector<DraftPart>{DraftPart::stairs(
				        r.x1 - kWallGap - L, a, 0, steps, rise, run, width)};
		    }
	    });
}

}  // namespace semnav::detail
