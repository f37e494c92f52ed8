/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/math/TPoint2D.h>
#include <semnav/common/Label.h>
#include <semnav/planning/CnnPlanner.h>
#include <semnav/planning/DiffusionField.h>
#include <semnav/planning/GoalLayer.h>
#include <semnav/planning/PlannedPath.h>
#include <semnav/planning/PlanningErrors.h>
#include <semnav/planning/TraversabilityBuilder.h>
#include <semnav/planning/TraversabilityGrid.h>

#include <cstdint>
#include <memory>
#include <mutex>

namespace semnav
{
class SemanticMap;
namespace detail
{
struct PlanCache;
struct GoalKey;
}  // namespace detail

/** The map has no (reported) instance of the requested label. */
class NoInstanceError : public PlanningError
{
	using PlanningError::PlanningError;
};

/** Adapter from a SemanticMap to the CNN planner: u from the map's
 * travel-cost layer, labels and occupancy (TraversabilityBuilder::
 * buildFromCost), goals from the map's objects. "Go to the nearest
 * <label>" puts the goal regions of every instance of the label in one goal
 * layer, so the diffusion picks the least expensive one by itself.
 *
 * Replanning is incremental (docs/navigation.md "Incremental replanning"):
 * the planner keeps the last plan's goal, u, goal layer and field. A plan
 * to the same goal on an unchanged map (SemanticMap::version()) with the
 * same extra obstacles only extracts a path from the new start; after a
 * change, u is rebuilt inside the changed cells' reach only
 * (SemanticMap::changesSince()), the goal layer is updated, and the field
 * is repaired from the cells whose u or goal changed
 * (CnnPlanner::repairField). Every plan equals a fresh planner's, bit for
 * bit. The cache is mutable behind a mutex: the methods stay const and
 * callable from several threads (one plan at a time). */
class SemanticPlanner
{
public:
	/** How the last plan got its field. */
	enum class FieldUpdate
	{
		/** From scratch: first plan, another goal or profile, the grid
		 * grew, or a repair fell back. */
		Full,
		/** Repaired from the changed cells. */
		Repair,
		/** Unchanged: only the path was extracted. */
		Reuse
	};
	/** Counts since construction (for a caller's report). */
	struct Counters
	{
		std::size_t fullFields = 0;
		std::size_t repairs = 0;
		std::size_t reuses = 0;
		/** Repairs that fell back to a full field (also in fullFields). */
		std::size_t repairFallbacks = 0;
		/** Start-bounded repairs that left work pending, and pending work
		 * finished later (another start, a Plan copy, the next change). */
		std::size_t boundedRepairs = 0;
		std::size_t pendingFinished = 0;
		/** Cells whose u or goal changed, summed over the repairs. */
		std::size_t changedCells = 0;
		/** Cells the repairs took from their queues (their work). */
		std::size_t repairedCells = 0;
		/** u rebuilt over the whole grid / only around changed cells. */
		std::size_t fullTraversability = 0;
		std::size_t partialTraversability = 0;
		/** The last plan's field update and its time (u, goals, field;
		 * path and copies not included) (ms). */
		FieldUpdate last = FieldUpdate::Full;
		double lastMilliseconds = 0;
	};

	struct Plan
	{
		PlannedPath path;
		DiffusionField field;
		TraversabilityGrid u;
		GoalLayer goals;
		CellIndex start;
		/** Label planned to (Unknown for a point goal). */
		Label goalLabel = Label::Unknown;
		/** Object reached (0 for a point goal). */
		int goalObjectId = 0;
	};

	/** A Plan whose u, goals and field are shared with the planner's
	 * cache instead of copied (~20 MB at 1000 x 1000: 40-60 ms on the
	 * project's VM, page faults of fresh memory included, far more than a
	 * repair). They stay valid
	 * and unchanged while held; the planner copies one before changing it
	 * only if a plan still holds it then, so drop plans that are done. */
	struct SharedPlan
	{
		PlannedPath path;
		std::shared_ptr<const DiffusionField> field;
		std::shared_ptr<const TraversabilityGrid> u;
		std::shared_ptr<const GoalLayer> goals;
		CellIndex start;
		Label goalLabel = Label::Unknown;
		int goalObjectId = 0;
		/** False after a start-bounded repair left work pending
		 * (setStartBoundedRepair): the field is then exact on the start's
		 * best paths only (PendingRepair); path, u and goals are exact. */
		bool fieldComplete = true;
		/** The same as a Plan (copies). */
		Plan copy() const;
	};

	SemanticPlanner(
	    const SemanticMap& map, const CnnPlanner::TOptions& cnn,
	    const TraversabilityBuilder::TOptions& traversability);
	~SemanticPlanner();
	SemanticPlanner(const SemanticPlanner&) = delete;
	SemanticPlanner& operator=(const SemanticPlanner&) = delete;

	/** Least-cost path from (x, y) to any instance of `label`, a goal
	 * class of the ClassRegistry. Throws NoInstanceError (also for a class
	 * that is no goal), StartOutsideMapError, StartBlockedError,
	 * EmptyGoalError, NoPathError. */
	Plan toLabel(double x, double y, Label label, CostProfile profile) const;
	/** Path to a given object of the map: one it reports
	 * (SemanticMap::instances()); NoInstanceError for any other id. */
	Plan toObject(double x, double y, int objectId, CostProfile profile) const;
	/** Path to the cells within goal_reach_m of (gx, gy). */
	Plan toPoint(
	    double x, double y, double gx, double gy, CostProfile profile) const;

	/** As toLabel, toObject and toPoint, sharing the grids (SharedPlan). */
	SharedPlan toLabelShared(
	    double x, double y, Label label, CostProfile profile) const;
	SharedPlan toObjectShared(
	    double x, double y, int objectId, CostProfile profile) const;
	SharedPlan toPointShared(
	    double x, double y, double gx, double gy, CostProfile profile) const;

	/** Obstacles the map does not hold (e.g. sensed by the robot while
	 * driving), world frame: their cells count as occupied (inflated like
	 * map obstacles) in every later plan. */
	void setExtraObstacles(std::vector<mrpt::math::TPoint2D> points);
	const std::vector<mrpt::math::TPoint2D>& extraObstacles() const
	{
		return m_extraObstacles;
	}

	/** Start-bounded repairs (off by default): a repair stops once the
	 * field is exact for the path from the plan's start
	 * (CnnPlanner::repairFieldFrom); the rest is finished before a plan
	 * from another start, a Plan copy (toLabel, toObject, toPoint) or the
	 * next change. Shared plans then may hold a field exact only on the
	 * start's best paths (SharedPlan::fieldComplete); their path is the
	 * full recompute's, bit for bit. */
	void setStartBoundedRepair(bool on);

	/** u of the whole map for a profile (the cached one when it is up to
	 * date). */
	TraversabilityGrid traversability(CostProfile profile) const;

	Counters counters() const;
	/** Forgets the cached plan: the next one is computed from scratch. */
	void clearCache();

private:
	/** The plan to `key` from (x, y), refreshing the cache first; with a
	 * complete field when `complete`. */
	SharedPlan run(
	    double x, double y, const detail::GoalKey& key,
	    bool complete = false) const;
	/** Finishes the pending work of a start-bounded repair: all of it, or
	 * what the path from `start` needs. */
	void finishPending(const CellIndex* start) const;
	/** The goal keys of toLabel, toObject and toPoint (checked). */
	detail::GoalKey labelKey(Label label, CostProfile profile) const;
	detail::GoalKey objectKey(int objectId, CostProfile profile) const;
	detail::GoalKey pointKey(double gx, double gy, CostProfile profile) const;
	/** Brings the cache to the map, the extra obstacles and `key`. */
	void refresh(const detail::GoalKey& key, const CellIndex& start) const;
	/** Rebuilds u, goals and field from scratch. */
	void rebuild(
	    const detail::GoalKey& key, std::vector<std::size_t> extraCells,
	    const CellIndex& start) const;
	/** u of the cells of `window` (clipped) as a grid of its own. */
	TraversabilityGrid traversabilityIn(
	    const CellRect& window, CostProfile profile,
	    const std::vector<std::size_t>& extraCells) const;
	/** Writes u after a change of the inputs in `inputs` into the cache's
	 * spare u; returns the cells where it may differ from the cached u. */
	CellRect updateTraversability(
	    const CellRect& inputs, CostProfile profile,
	    const std::vector<std::size_t>& extraCells) const;
	/** The field for the spares: repaired from `changed` (same goal; bounded
	 * by `start` when so set) or computed from scratch. */
	void updateField(
	    bool sameGoal, const CellRect& changed, const CellIndex& start) const;
	/** Goal cells (cell, id), by cell. */
	std::vector<std::pair<std::size_t, int>> goalCellsOf(
	    const detail::GoalKey& key) const;
	/** Sorted cells of the extra obstacles inside the grid. */
	std::vector<std::size_t> extraObstacleCells() const;

	const SemanticMap& m_map;
	CnnPlanner m_cnn;
	TraversabilityBuilder m_builder;
	std::vector<mrpt::math::TPoint2D> m_extraObstacles;
	bool m_startBounded = false;
	mutable std::mutex m_mutex;
	std::unique_ptr<detail::PlanCache> m_cache;
	mutable Counters m_counters;
};

}  // namespace semnav
