/* semnav: semantic navigation from tilting-laser sweeps */
// Internal: what SemanticPlanner keeps of its last plan.
#pragma once

#include <semnav/common/CellRect.h>
#include <semnav/common/Label.h>
#include <semnav/planning/DiffusionField.h>
#include <semnav/planning/GoalLayer.h>
#include <semnav/planning/PendingRepair.h>
#include <semnav/planning/TraversabilityBuilder.h>
#include <semnav/planning/TraversabilityGrid.h>

#include <cstdint>
#include <map>
#include <memory>
#include <utility>
#include <vector>

namespace semnav::detail
{
/** The goal of a plan: a label, an object or a point, and the profile. */
struct GoalKey
{
	enum class Kind
	{
		Label,
		Object,
		Point
	};
	Kind kind = Kind::Point;
	Label label = Label::Unknown;
	int objectId = 0;
	double x = 0, y = 0;
	CostProfile profile = CostProfile::Shortest;

	bool operator==(const GoalKey& o) const
	{
		return kind == o.kind && label == o.label && objectId == o.objectId &&
		       x == o.x && y == o.y && profile == o.profile;
	}
};

/** Goal cells (cell index, goal id), by cell index. */
using GoalCells = std::vector<std::pair<std::size_t, int>>;

/** Goal regions of the map's objects (SemanticMap::goalRegion), kept
 * while no map change can reach them. */
struct ObjectRegions
{
	bool valid = false;
	/** The radius they were computed for. */
	double reach = -1;
	/** Per object id: bounding box of its cells in the "objects" layer (a
	 * superset: a cell that lost the id stays in); none: no cell. */
	std::map<int, CellRect> painted;
	/** Per object id: its region's cells. */
	std::map<int, std::vector<std::size_t>> cells;
};

/** The last plan's inputs and field. `spareU` and `spareGoals` equal `u`
 * and `goals` between plans; an update writes the new ones there, repairs
 * the field from (u, goals) to them, swaps, and copies the changed cells
 * back into the spares. u, goals and field are shared with the plans
 * handed out (SemanticPlanner::SharedPlan): owned() copies one before it
 * is changed while a plan still holds it. */
struct PlanCache
{
	bool valid = false;
	GoalKey key;
	std::uint64_t mapVersion = 0;
	/** Cells of the extra obstacles, sorted. */
	std::vector<std::size_t> extraCells;
	std::shared_ptr<TraversabilityGrid> u, spareU;
	std::shared_ptr<GoalLayer> goals, spareGoals;
	GoalCells goalCells;
	ObjectRegions regions;
	std::shared_ptr<DiffusionField> field;
	/** Work left by a start-bounded repair of `field`; it refers to *u and
	 * *goals, so it is finished or dropped before they change. */
	PendingRepair pending;
};

/** *p, writable: a copy of it first while someone else holds it. */
template <class T>
T& owned(std::shared_ptr<T>& p)
{
	if (!p)
		p = std::make_shared<T>();
	else if (p.use_count() > 1)
		p = std::make_shared<T>(*p);
	return *p;
}

}  // namespace semnav::detail
