/* semnav: semantic navigation from tilting-laser sweeps */
// Internal: incremental repair of a converged diffusion field (see
// CnnPlanner::repairField).
#pragma once

#include <semnav/common/CellRect.h>
#include <semnav/planning/FieldRepairStats.h>
#include <semnav/planning/GoalLayer.h>
#include <semnav/planning/PendingRepair.h>
#include <semnav/planning/TraversabilityGrid.h>

#include <cstddef>
#include <cstdint>
#include <vector>

#include "BucketQueue.h"
#include "DiffusionKernels.h"

namespace semnav::detail
{
/** Brings x, the fixed point of eq. (10) for (oldU, oldGoals), to the fixed
 * point for (newU, newGoals), in place, touching only the cells whose value
 * may change. Two queues, interleaved level by level (highest value
 * first), as LPA* / D* Lite interleave under- and overconsistent cells:
 * - examine (underconsistent cells), by stored value: a cell downstream of
 *   a raised cost or a lost goal keeps its value when a neighbour still
 *   offers it under the new costs, otherwise it drops to -infinity, its
 *   dependants (neighbours whose value came through it) are examined in
 *   turn and its own raise is deferred;
 * - raise (overconsistent cells), by value: a popped cell offers
 *   x - (a + u) to its neighbours and raises those below it; a deferred
 *   raise takes eq. (10) from the neighbours only once every cell above
 *   its level is settled.
 * A level's examinations come before its raises, so every value written
 * is one that some path achieves (none comes from a stale value). Every
 * value is the same floating-point expression as in the full diffusion,
 * x_j - (a + u_j), so the result is the same fixed point, bit for bit.
 *
 * Focused on a start cell, as A* / D* Lite, the queues order cells by
 * cost to go plus focus, kFocusWeight times the octile distance to the
 * start (a consistent lower bound with a margin of half a step, two
 * buckets, so that order still settles every support first); a bounded
 * run() stops once no queued level can change the start's value: x is
 * then exact on every cell whose cost to go plus focus is below
 * settledCost() (every cell of the start's best paths), and never above
 * the fixed point where it is not, within it; the queues are the pending
 * work, which a later run() finishes (it needs newU and newGoals,
 * unchanged, alive). */
class FieldRepairer
{
public:
	/** Focused on `start` when not null. */
	FieldRepairer(
	    const TraversabilityGrid& newU, const GoalLayer& newGoals,
	    const CellIndex* start);

	static constexpr double kFocusWeight = PendingRepair::kFocusWeight;

	/** Collects the cells inside `rect` (clipped to the grid) whose u or
	 * goal status differs between (oldU, oldGoals) and the new inputs; the
	 * old inputs are not used after it. */
	void collectChanges(
	    const CellRect& rect, const TraversabilityGrid& oldU,
	    const GoalLayer& oldGoals);
	std::size_t changedCount() const { return m_changed.size(); }
	/** Goal cells of oldGoals that are no goal in newGoals. */
	std::size_t removedGoalCells() const { return m_removedGoals; }
	/** Cells that stopped being a traversable goal (a source of value L). */
	std::size_t lostSources() const { return m_lostSources; }

	/** Bucket width of the queues: a quarter of the least step cost. */
	static double bucketWidth(double resolution) { return resolution / 4; }
	/** True when the queues order the cells exactly enough: L's rounding
	 * unit well below the bucket width (L <= ~1e12 at 5 cm), and cell
	 * indices within 32 bits. */
	static bool applicable(const GridGeometry& g, double L);
	static constexpr const char* kWorkLimitReached =
	    "the repair reached its work limit";
	static constexpr const char* kValueTooLarge =
	    "a value's rounding unit exceeds 1/64 of a cell (costs over ~1e11 "
	    "at 5 cm)";

	/** Seeds the queues from the changes; x is the old fixed point. */
	void seed(std::vector<double>& x);
	/** Repairs x (the vector seeded, or a copy of it) until the queues are
	 * empty or, `bounded` (and focused), until x is exact for the start's
	 * paths.
	 * Returns nullptr when so, else why it stopped (x then partly
	 * repaired): more than `workLimit` cells taken from the queues in all,
	 * or a value too far below L for the buckets to order it exactly.
	 * Adds its counts to `stats`. */
	const char* run(
	    std::vector<double>& x, std::size_t workLimit, bool bounded,
	    FieldRepairStats& stats);
	/** No pending work: x is the new fixed point. */
	bool done() const
	{
		return m_examine.empty() && m_raise.empty() && m_afterExamining.empty();
	}
	/** After a bounded run: every cell whose cost to go plus focus is
	 * below this is exact (infinity when done). */
	double settledCost() const;
	bool focused() const { return m_focused; }
	const CellIndex& start() const { return m_start; }

private:
	/** A raise entry whose cell takes eq. (10) from its neighbours. */
	static constexpr std::size_t kDeferred = std::size_t(1) << 63;

	struct Change
	{
		std::size_t cell;
		double oldU;
		bool oldSource;
	};

	bool blockedNew(std::size_t i) const { return m_newU[i] >= m_L; }
	bool sourceNew(std::size_t i) const
	{
		return m_newGoals.isGoal(i) && m_newU[i] < m_L;
	}
	/** Calls f(j, k) for each neighbour j of i inside the grid, k the
	 * direction (kDr, kDc). */
	template <class F>
	void forNeighbours(std::size_t i, const F& f) const;

	/** Within one cell of the changed cells' bounding box. */
	bool nearChange(std::size_t i) const;
	/** u of i before the change (i near the changes). */
	double oldUNear(std::size_t i) const;
	/** Pushes the neighbours whose value came through i (value v, entry
	 * cost u) to the examine queue. */
	void pushDependants(std::size_t i, double v, double u);
	/** Keeps v at i when a neighbour still offers it under the new costs
	 * (or i is a goal), else invalidates i. */
	void examine(std::size_t i, double v);
	/** Eq. (10) at i from its neighbours: taken when its level is
	 * settled (at or above `level`), else deferred to its level. */
	void raiseFromNeighbours(std::size_t i, std::int64_t level);
	/** raiseFromNeighbours at `level`, or, examining first (unbounded),
	 * once every examination is done. */
	void deferRaise(std::size_t i, std::int64_t level);
	/** A popped cell offers its value to its neighbours. */
	void propagate(std::size_t i, double v);
	/** True when no level from `level` on can change the start's value. */
	bool settles(std::int64_t level) const;
	/** kFocusWeight times the octile distance from i to the start. */
	double focus(std::size_t i) const;
	/** The queues' order of value v at i: v less the focus (focused). */
	double priority(double v, std::size_t i) const
	{
		return m_focused ? v - focus(i) : v;
	}

	const bool m_focused;
	const CellIndex m_start;
	double* m_x = nullptr;
	const std::vector<double>& m_newU;
	const GoalLayer& m_newGoals;
	const GridGeometry m_g;
	const double m_L;
	const Steps m_a;
	/** Values below -m_maxMagnitude round by more than 1/16 of a bucket. */
	const double m_maxMagnitude;
	/** Index offsets of the 8 neighbours (kDr, kDc). */
	std::ptrdiff_t m_offset[8];
	std::vector<Change> m_changed;
	CellRect m_changedBox, m_nearBox;
	/** Old u over m_nearBox. */
	std::vector<double> m_oldNear;
	std::size_t m_removedGoals = 0, m_lostSources = 0;
	std::size_t m_work = 0, m_invalidated = 0, m_raised = 0;
	/** m_invalidated, m_raised, m_work at the end of the last run. */
	std::size_t m_reported[3] = {0, 0, 0};
	std::int64_t m_settledLevel = -1;
	/** Unbounded: examinations first, then the raises of
	 * m_afterExamining (the two phases of LPA*'s batch form). */
	bool m_examineFirst = false;
	std::vector<std::size_t> m_afterExamining;
	BucketQueue m_examine, m_raise;
};

}  // namespace semnav::detail
