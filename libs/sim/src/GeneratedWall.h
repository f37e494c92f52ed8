/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once
// A straight wall with openings (doors, double doors, open gaps) for
// SceneGenerator (src/ only).

#include <string>
#include <vector>

#include "SceneDraft.h"

namespace semnav::detail
{
/** An opening in a GeneratedWall. */
struct WallOpening
{
	enum class Type
	{
		Door,
		DoubleDoor,
		Gap
	};
	Type type = Type::Gap;
	/** Centre along the wall and width of the gap in the wall (m). */
	double center = 0, width = 1;
	/** Door leaf height; lintel above the opening from `lintelBottom` up
	 * (none when <= 0). */
	double leafHeight = 2.0, lintelBottom = 2.0;
	/** How far the leaf's front face sits behind the wall's front face. */
	double inset = 0.02;

	/** Random opening of `type`: leaves 0.8-1.2 m (single) or 1.4-2.0 m
	 * (double) wide in a gap 4 cm wider; open gaps 1.0-1.6 m; leaves
	 * recessed 2-10 cm or (nearly) flush, 5-10 mm, within `wallThickness`. */
	static WallOpening random(
	    GeneratorRandom& rng, Type type, double wallThickness,
	    double maxLeafHeight);
	bool isDoor() const { return type != Type::Gap; }
	std::string describe() const;
};

/** A straight wall along x (at y = `across`) or along y (at x = `across`),
 * from `from` to `to`, with openings; `front` (+1/-1) is the side door
 * insets are measured from. */
class GeneratedWall
{
public:
	bool alongX = true;
	double across = 0, from = 0, to = 0;
	double thickness = 0.1, height = 2.7;
	int front = 1;
	std::vector<WallOpening> openings;

	/** Adds the wall pieces, lintels and door leaves to `draft`. */
	void addTo(SceneDraft& draft) const;

private:
	void addBox(
	    SceneDraft& d, Label l, double a0, double a1, double z0, double z1,
	    double acrossCenter, double acrossSize) const;
};

}  // namespace semnav::detail
