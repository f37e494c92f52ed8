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

/** The work a start-bounded repair (CnnPlanner::repairFieldFrom) left:
 * the field is exact on every cell whose value exceeds settledAbove() (the
 * start's path and every cell it compares), and below the full
 * recompute's value on the others. CnnPlanner::finishRepair does the rest.
 * It refers to the new traversability grid and goal layer of the repair:
 * they must stay alive and unchanged while work is pending. */
class PendingRepair
{
public:
	PendingRepair();
	~PendingRepair();
	PendingRepair(PendingRepair&&) noexcept;
	PendingRepair& operator=(PendingRepair&&) noexcept;

	/** No work left: the field is the full recompute's, bit for bit. */
	bool empty() const;
	/** Every cell whose field value exceeds this is exact; -infinity when
	 * empty. */
	double settledAbove() const;
	/** Forgets the work (the field is then only exact above
	 * settledAbove(): recompute it before any other use). */
	void clear();

private:
	friend class CnnPlanner;
	std::unique_ptr<detail::FieldRepairer> m_repairer;
	const TraversabilityGrid* m_u = nullptr;
	const GoalLayer* m_goals = nullptr;
	std::size_t m_workLimit = 0;
};

}  // namespace semnav
