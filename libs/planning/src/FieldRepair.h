/* semnav: semantic navigation from tilting-laser sweeps */
// Internal: incremental repair of a converged diffusion field (see
// CnnPlanner::repairField).
#pragma once

#include <semnav/common/CellRect.h>
#include <semnav/planning/FieldRepairStats.h>
#include <semnav/planning/GoalLayer.h>
#include <semnav/planning/TraversabilityGrid.h>

#include <cstddef>
#include <vector>

#include "BucketQueue.h"
#include "DiffusionKernels.h"

namespace semnav::detail
{
/** Brings x, the fixed point of eq. (10) for (oldU, oldGoals), to the fixed
 * point for (newU, newGoals), in place, touching only the cells whose value
 * may change. Two phases, as LPA* / D* Lite do for a shortest-path tree:
 * - invalidate (underconsistent cells): in decreasing order of old value,
 *   a cell downstream of a raised cost or a lost goal keeps its value when
 *   a neighbour still offers it under the new costs, otherwise it drops to
 *   -infinity and its dependants (neighbours whose value came through it)
 *   are examined in turn;
 * - propagate (overconsistent cells): the invalidated cells, the changed
 *   cells and the neighbours of cheaper or freed cells take eq. (10)'s
 *   value from their neighbours, then a Dijkstra-like front (highest value
 *   first, in buckets) raises every cell whose eq. (10) term improved.
 * Every value is the same floating-point expression as in the full
 * diffusion, x_j - (a + u_j), so the result is the same fixed point, bit for
 * bit. */
class FieldRepairer
{
public:
	FieldRepairer(
	    std::vector<double>& x, const TraversabilityGrid& oldU,
	    const GoalLayer& oldGoals, const TraversabilityGrid& newU,
	    const GoalLayer& newGoals);

	/** Collects the changed cells inside `rect` (clipped to the grid). */
	void collectChanges(const CellRect& rect);
	const std::vector<std::size_t>& changed() const { return m_changed; }
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

	/** Both phases. Returns nullptr when done, else why it stopped (x then
	 * partly repaired): more than `workLimit` cells taken from the queues,
	 * or a value too far below L for the buckets to order it exactly. */
	const char* run(std::size_t workLimit, FieldRepairStats& stats);

private:
	bool blockedNew(std::size_t i) const { return m_newU[i] >= m_L; }
	bool sourceOld(std::size_t i) const
	{
		return m_oldGoals.isGoal(i) && m_oldU[i] < m_L;
	}
	bool sourceNew(std::size_t i) const
	{
		return m_newGoals.isGoal(i) && m_newU[i] < m_L;
	}
	/** Calls f(j, k) for each neighbour j of i inside the grid, k the
	 * direction (kDr, kDc). */
	template <class F>
	void forNeighbours(std::size_t i, const F& f) const;

	/** Pushes the neighbours whose value came through i (value v, entry
	 * cost u). */
	void pushDependants(std::size_t i, double v, double u);
	/** Sets x(i) to -infinity and pushes its dependants. */
	void invalidateCell(std::size_t i, double v, double u);
	/** Within one cell of the changed cells' bounding box. */
	bool nearChange(std::size_t i) const;
	/** Keeps v at i when a neighbour still offers it under the new costs
	 * (or i is a goal), else invalidates i. */
	void examine(std::size_t i, double v);
	const char* invalidate(std::size_t workLimit);
	/** Eq. (10) at i from its neighbours; raises x(i) and queues it. */
	void raiseFromNeighbours(std::size_t i);
	const char* propagate(std::size_t workLimit);

	std::vector<double>& m_x;
	const std::vector<double>& m_oldU;
	const std::vector<double>& m_newU;
	const GoalLayer& m_oldGoals;
	const GoalLayer& m_newGoals;
	const GridGeometry m_g;
	const double m_L;
	const Steps m_a;
	/** Values below -m_maxMagnitude round by more than 1/16 of a bucket. */
	const double m_maxMagnitude;
	/** Index offsets of the 8 neighbours (kDr, kDc). */
	std::ptrdiff_t m_offset[8];
	std::vector<std::size_t> m_changed, m_invalidated;
	CellRect m_changedBox;
	std::size_t m_removedGoals = 0, m_lostSources = 0;
	std::size_t m_work = 0, m_raised = 0;
	BucketQueue m_queue;
};

}  // namespace semnav::detail
