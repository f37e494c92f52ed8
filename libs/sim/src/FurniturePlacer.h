/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once
// Places furniture in the rectangular rooms of a generated scene
// (SceneGenerator, src/ only): against walls, in corners or free-standing,
// clear of other objects and of the draft's keep-out lanes.

#include <functional>
#include <vector>

#include "SceneDraft.h"

namespace semnav::detail
{
/** Interior of a room (wall faces), axis-aligned. */
struct RoomRect
{
	double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
	double width() const { return x1 - x0; }
	double depth() const { return y1 - y0; }
};

class FurniturePlacer
{
public:
	/** A spot against a wall: centre and the yaw (deg) facing into the
	 * room. */
	struct Spot
	{
		double x, y, yawDeg;
	};

	explicit FurniturePlacer(SceneDraft& draft) : m_draft(draft) {}

	/** Basin box on a pedestal, top at 0.78-0.92 m, against a wall. */
	bool washbasin(const RoomRect& r);
	/** Cylinder r 0.12-0.20 m, 0.30-0.50 m high; `where`: 0 wall,
	 * 1 corner, 2 free-standing. */
	bool wastebasket(const RoomRect& r, int where);
	/** Box 0.35-0.6 m deep, 0.5-1.3 m wide, 0.7-1.9 m high, against a wall. */
	bool cabinet(const RoomRect& r);
	/** A small box, or with p 0.3 a plantPot(), close to a wall. */
	bool clutter(const RoomRect& r);
	/** A pot of a wastebasket's size with a plant: foliage wider than the
	 * pot above it (label obstacle). */
	bool plantPot(const RoomRect& r);
	/** A table on four legs with up to `chairs` chairs around it. */
	bool tableWithChairs(const RoomRect& r, int chairs);
	/** 3-7 steps climbing toward wall `side` (0 south, 1 north, 2 west,
	 * 3 east). */
	bool stairs(const RoomRect& r, int side);

	/** A random spot against one of the room's walls for an item `depth`
	 * deep (into the room) and `width` wide, `gap` off the wall. */
	Spot wallSpot(const RoomRect& r, double depth, double width, double gap);

private:
	/** Tries up to 40 candidates; adds the first free one. */
	bool place(
	    Label label, const std::function<std::vector<DraftPart>()>& candidate);
	std::vector<DraftPart> chair(double x, double y, double yawDeg);

	SceneDraft& m_draft;
};

}  // namespace semnav::detail
