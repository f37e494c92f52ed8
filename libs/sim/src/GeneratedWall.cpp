/* semnav: semantic navigation from tilting-laser sweeps */
#include "GeneratedWall.h"

#include <algorithm>

namespace semnav::detail
{
namespace
{
constexpr double kLeafThickness = 0.04;
/** Gap between a door leaf and its frame on each side. */
constexpr double kLeafClearance = 0.02;
}  // namespace

WallOpening WallOpening::random(
    GeneratorRandom& rng, Type type, double wallThickness, double maxLeafHeight)
{
	WallOpening o;
	o.type = type;
	if (type == Type::Gap)
	{
		o.width = rng.uniform(1.0, 1.6);
		o.lintelBottom = rng.chance(0.5) ? rng.uniform(2.0, 2.3) : 0.0;
		return o;
	}
	const double leaf =
	    type == Type::Door ? rng.uniform(0.8, 1.2) : rng.uniform(1.4, 2.0);
	o.width = leaf + 2 * kLeafClearance;
	o.leafHeight = rng.uniform(1.95, maxLeafHeight);
	o.lintelBottom = o.leafHeight;
	const double maxInset = std::min(0.10, wallThickness - kLeafThickness);
	o.inset = rng.chance(0.6) && maxInset > 0.03 ? rng.uniform(0.02, maxInset)
	                                             : rng.uniform(0.005, 0.01);
	return o;
}

std::string WallOpening::describe() const
{
	const std::string w = formatNumber(width);
	switch (type)
	{
		case Type::Gap:
			return "open gap " + w + " m";
		case Type::Door:
			return "door in a " + w + " m gap, inset " + formatNumber(inset);
		case Type::DoubleDoor:
			return "double door in a " + w + " m gap, inset " +
			       formatNumber(inset);
	}
	return {};
}

void GeneratedWall::addBox(
    SceneDraft& d, Label l, double a0, double a1, double z0, double z1,
    double acrossCenter, double acrossSize) const
{
	const double c = 0.5 * (a0 + a1), len = a1 - a0;
	const double zc = 0.5 * (z0 + z1), h = z1 - z0;
	if (alongX)
		d.add(
		    l, {DraftPart::box(c, acrossCenter, zc, len, acrossSize, h)}, true);
	else
		d.add(
		    l, {DraftPart::box(acrossCenter, c, zc, acrossSize, len, h)}, true);
}

void GeneratedWall::addTo(SceneDraft& draft) const
{
	auto sorted = openings;
	std::sort(
	    sorted.begin(), sorted.end(),
	    [](const auto& a, const auto& b) { return a.center < b.center; });
	double start = from;
	for (const auto& o : sorted)
	{
		const double o0 = o.center - o.width / 2, o1 = o.center + o.width / 2;
		if (o0 - start > 0.01)
			addBox(draft, Label::Wall, start, o0, 0, height, across, thickness);
		start = o1;
		if (o.lintelBottom > 0 && o.lintelBottom < height - 0.01)
			addBox(
			    draft, Label::Wall, o0, o1, o.lintelBottom, height, across,
			    thickness);
		if (!o.isDoor()) continue;
		const double leafAcross =
		    across + front * (thickness / 2 - o.inset - kLeafThickness / 2);
		const double l0 = o0 + kLeafClearance, l1 = o1 - kLeafClearance;
		std::vector<DraftPart> leaves;
		const int n = o.type == WallOpening::Type::DoubleDoor ? 2 : 1;
		for (int k = 0; k < n; k++)
		{
			const double a0 = l0 + (l1 - l0) * k / n;
			const double a1 = l0 + (l1 - l0) * (k + 1) / n;
			const double c = 0.5 * (a0 + a1), len = a1 - a0;
			const double zc = o.leafHeight / 2;
			leaves.push_back(
			    alongX
			        ? DraftPart::box(
			              c, leafAcross, zc, len, kLeafThickness, o.leafHeight)
			        : DraftPart::box(
			              leafAcross, c, zc, kLeafThickness, len,
			              o.leafHeight));
		}
		draft.add(Label::Door, leaves, true);
	}
	if (to - start > 0.01)
		addBox(draft, Label::Wall, start, to, 0, height, across, thickness);
}

}  // namespace semnav::detail
