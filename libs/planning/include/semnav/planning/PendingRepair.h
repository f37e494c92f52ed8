/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/planning/GoalLayer.h>
#include <semnav/planning/TraversabilityGrid.h>

#include <cstddef>
#include <memory>

namespace semnav
{
namespace detail
{
class FieldRepairer;
}
class CnnPlanner;

/** The work a start-bounded repair (CnnPlanner::repairFieldFrom) left.
 * The repair orders cells by cost to go plus their focus, kFocusWeight
 * times their octile distance (m) to the start, as A* does; the field is
 * exact on every cell whose full-recompute cost to go plus focus is below
 * settledCost() (every cell of a best path from the start, and the start's
 * best path is the full recompute's), and no cell holds a value the
 * start's path extraction would prefer wrongly.
 * CnnPlanner::finishRepair does the rest. It refers to the new
 * traversability grid and goal layer of the repair: they must stay alive
 * and unchanged while work is pending. */
class PendingRepair
{
public:
	PendingRepair();
	~PendingRepair();
	PendingRepair(PendingRepair&&) noexcept;
	PendingRepair& operator=(PendingRepair&&) noexcept;

	/** Weight of the octile distance to the start in the repair's order
	 * (a lower bound of the cost from the start with a margin of half a
	 * step: the order still settles every cell after those it depends
	 * on). */
	static constexpr double kFocusWeight = 0.5;

	/** No work left: the field is the full recompute's, bit for bit. */
	bool empty() const;
	/** Every cell whose cost to go plus focus is below this is exact;
	 * infinity when empty. */
	double settledCost() const;
	/** The start the repair was bounded by. */
	CellIndex start() const;
	/** Forgets the work (the field is then only exact where settledCost()
	 * says: recompute it before any other use). */
	void clear();

private:
	friend class CnnPlanner;
	std::unique_ptr<detail::FieldRepairer> m_repairer;
	const TraversabilityGrid* m_u = nullptr;
	const GoalLayer* m_goals = nullptr;
	std::size_t m_workLimit = 0;
};

}  // namespace semnav
