/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <cstddef>
#include <string>

namespace semnav
{
/** What CnnPlanner::repairField did. After a fallback the counts are those
 * of the abandoned repair (0 when it did not start). */
struct FieldRepairStats
{
	/** True when the field was recomputed from scratch instead (see
	 * fallbackReason). */
	bool fullRecompute = false;
	/** Why the repair fell back to a full recompute; empty otherwise. */
	std::string fallbackReason;
	/** Cells whose u (blocked or not, cost) or goal status changed. */
	std::size_t changedCells = 0;
	/** Cells whose old value lost its support (an increase upstream) and
	 * were reset to -infinity before the propagation. */
	std::size_t invalidatedCells = 0;
	/** Cells whose value was raised by the propagation (counted once per
	 * raise). */
	std::size_t raisedCells = 0;
	/** Cells taken from the repair's queues to be examined or to offer
	 * their value (its work, which the work limit bounds; deferred raises
	 * are not counted). */
	std::size_t poppedCells = 0;
	/** Wall time of the repair (or of the full recompute) (ms). */
	double milliseconds = 0;
};

}  // namespace semnav
