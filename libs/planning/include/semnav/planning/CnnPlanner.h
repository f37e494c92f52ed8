/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/system/COutputLogger.h>
#include <semnav/common/CellRect.h>
#include <semnav/planning/DiffusionField.h>
#include <semnav/planning/FieldRepairStats.h>
#include <semnav/planning/GoalLayer.h>
#include <semnav/planning/PendingRepair.h>
#include <semnav/planning/PlannedPath.h>
#include <semnav/planning/TraversabilityGrid.h>

#include <string>

namespace semnav
{
/** Update schedules of the diffusion; both reach the same fixed point. */
enum class CnnSchedule
{
	/** In-place alternating raster passes (down, up), Gauss-Seidel style:
	 * each row is relaxed from the previous row, then along itself both
	 * ways; only columns next to cells that rose since are revisited; the
	 * grid is split into horizontal bands, one per thread. Stops when no
	 * cell is left unverified. Production. */
	Sweep,
	/** Synchronous eq. (10): every cell from the previous state. Reference
	 * for tests. */
	Jacobi
};

/** "sweep" / "jacobi"; throws PlanningError on other names. */
CnnSchedule cnnScheduleFromName(const std::string& name);
const char* cnnScheduleName(CnnSchedule s);

/** The path planner of the paper's sec. 3: a three-layer cellular neural
 * network (goal g, traversability u, diffusion x) on an N x M grid.
 *
 * Cost convention: cost(c0..cn) = sum over k = 1..n of (a(c_{k-1}, c_k) +
 * u(c_k)), a = resolution or resolution * sqrt(2) (eq. (8), 8-neighbourhood):
 * the start cell's u is not charged, every entered cell's u is, the goal
 * cell's included.
 *
 * Derivation. Eq. (10) passes x_kl - a - u_kl from the neighbour kl the
 * robot would enter, so at the fixed point x(c) = x(goal) - cost(c -> goal)
 * along the best path. Eq. (9) starts a goal cell at g - u = L - u(goal):
 * the goal's u would be charged twice (on entry and in x(goal)), biasing the
 * choice among goals. Here goal cells start at L, so L - x(c) is exactly the
 * min cost from c to the goal set in the convention above. Non-goal cells
 * start at -infinity instead of -u (the limit of a very large L: -u would
 * make every cell a spurious source of value -u) and blocked cells (u >= L,
 * C_occ, u = infinity in eq. (7)) stay at -infinity and are never entered.
 * Eq. (12) is read as the max of the same neighbour term as eq. (10),
 * x_nm - a - u_nm (the literal max of x_nm ignores step length and entry
 * cost and is not optimal); at the fixed point that term equals x of the
 * current cell, so each step raises x by exactly its cost and the reported
 * cost (summed along the path) equals L - x(start) up to rounding. x is
 * double and every schedule evaluates the same expression x_kl - (a + u_kl):
 * they reach the same floating-point fixed point, bit for bit (it is unique
 * while each step lowers x by more than its rounding unit, e.g. L <= 1e9
 * with cells >= 1 mm). Float would lose 1e-6 relative accuracy over long
 * paths near L. */
class CnnPlanner : public mrpt::system::COutputLogger
{
public:
	/** Options, INI section [CnnPlanner] (config/planning.ini). */
	struct TOptions : public mrpt::config::CLoadableOptions
	{
		void loadFromConfigFile(
		    const mrpt::config::CConfigFileBase& c,
		    const std::string& section) override;
		void saveToConfigFile(
		    mrpt::config::CConfigFileBase& c,
		    const std::string& section) const override;
		static const std::vector<std::string>& knownKeys();

		/** schedule: sweep (production) | jacobi (reference). */
		CnnSchedule schedule = CnnSchedule::Sweep;
		/** threads: 0 = all cores. */
		int threads = 0;
		/** max_iterations: passes (sweep) or updates (jacobi) before
		 * NotConvergedError; 0 = no limit. */
		int maxIterations = 0;
	};

	CnnPlanner();
	explicit CnnPlanner(const TOptions& options);

	const TOptions& options() const { return m_options; }
	TOptions& options() { return m_options; }

	/** Start cell of (x, y); throws StartOutsideMapError. */
	static CellIndex startCell(
	    const GridGeometry& geometry, double x, double y);

	/** Throws StartOutsideMapError, StartBlockedError, EmptyGoalError (or
	 * PlanningError when u and goals differ in geometry). */
	static void checkInputs(
	    const TraversabilityGrid& u, const GoalLayer& goals,
	    const CellIndex& start);
	/** The start checks of checkInputs (StartOutsideMapError,
	 * StartBlockedError), without the pass over the goals. */
	static void checkStart(const TraversabilityGrid& u, const CellIndex& start);

	/** Diffusion to the fixed point (eq. (9)-(11)). Throws EmptyGoalError,
	 * NotConvergedError, PlanningError. */
	DiffusionField computeField(
	    const TraversabilityGrid& u, const GoalLayer& goals) const;
	/** As computeField, into `field`, reusing its storage (no 8 bytes per
	 * cell allocated when the grid's size is unchanged); on an exception
	 * `field` is left invalid. */
	void computeFieldInto(
	    const TraversabilityGrid& u, const GoalLayer& goals,
	    DiffusionField& field) const;

	/** Default work limit of repairField: the repair falls back to a full
	 * recompute once it has taken more than this fraction of the grid's
	 * cells from its queues (past it the raster sweep is cheaper). */
	static constexpr double kRepairMaxWorkFraction = 0.1;

	/** Incremental replanning: turns `field`, the converged field of
	 * (oldU, oldGoals), into the field of (newU, newGoals), in place,
	 * repairing only the cells whose value may change: the same fixed
	 * point as computeField(newU, newGoals), bit for bit (docs/navigation.md
	 * "Incremental repair").
	 *
	 * Cost increases, new obstacles and lost goal cells first invalidate
	 * the cells whose value came through them (highest value first, a cell
	 * keeping its value while a neighbour still offers it), then the
	 * invalidated cells, the changed cells and the neighbours of cheaper or
	 * freed cells are re-propagated highest value first, as Dijkstra does.
	 *
	 * @param changed Cells that may differ between (oldU, oldGoals) and
	 *   (newU, newGoals), clipped to the grid; nullptr = the whole grid is
	 *   compared. The caller guarantees that no cell outside it differs.
	 * @param maxWorkFraction Work limit, as a fraction of the grid's cells
	 *   (<= 0: always recompute; infinity: never fall back on work).
	 *
	 * Falls back to computeField(newU, newGoals) (fullRecompute, with the
	 * reason) when the grid's geometry or L changed, when every goal cell of
	 * oldGoals was removed (the goal moved: every value came from it), when
	 * more cells changed than the work limit, or when the work limit is
	 * reached. Throws EmptyGoalError (field untouched) when no traversable
	 * goal cell is left, PlanningError when newU and newGoals differ in
	 * geometry or `field` does not match oldU, NotConvergedError from a
	 * fallback as computeField (field then invalid). After a repair,
	 * field.iterations and field.rowUpdates are 0 and field.milliseconds is
	 * the repair's time. */
	FieldRepairStats repairField(
	    DiffusionField& field, const TraversabilityGrid& oldU,
	    const GoalLayer& oldGoals, const TraversabilityGrid& newU,
	    const GoalLayer& newGoals, const CellRect* changed = nullptr,
	    double maxWorkFraction = kRepairMaxWorkFraction) const;

	/** Start-bounded repairField, as D* Lite stops once the start is
	 * consistent: the queues are ordered by cost to go plus half the
	 * octile distance to `start` (as A* orders a search), and the repair
	 * stops once no queued level can change the start's value, leaving the
	 * rest in `pending` (docs/navigation.md "Start-bounded repair"). The
	 * field is then exact on every cell of a best path from `start`
	 * (PendingRepair::settledCost), and tracePath from `start` gives the
	 * full recompute's path, bit for bit. finishRepair does the rest
	 * (before any other use of the field). `pending` must be empty
	 * (PlanningError otherwise); it refers to newU and newGoals until it
	 * is. A start outside the grid, blocked or cut off from the goals
	 * repairs the whole field. Throws and falls back as repairField
	 * (pending then empty); the work limit counts the finished work too. */
	FieldRepairStats repairFieldFrom(
	    const CellIndex& start, DiffusionField& field,
	    const TraversabilityGrid& oldU, const GoalLayer& oldGoals,
	    const TraversabilityGrid& newU, const GoalLayer& newGoals,
	    PendingRepair& pending, const CellRect* changed = nullptr,
	    double maxWorkFraction = kRepairMaxWorkFraction) const;
	/** Continues the work of repairFieldFrom on `field` (the field it
	 * repaired, or a copy of it): all of it (the field is then the full
	 * recompute's, bit for bit), or nothing more when `start` is the
	 * repair's (its order is focused on that start: any other start
	 * finishes all of it). Past the work limit, recomputes the field
	 * (fullRecompute). */
	FieldRepairStats finishRepair(
	    DiffusionField& field, PendingRepair& pending,
	    const CellIndex* start = nullptr) const;

	/** Path by eq. (12) from `start` over a converged field. Throws
	 * StartOutsideMapError, StartBlockedError, NoPathError. */
	static PlannedPath extractPath(
	    const DiffusionField& field, const TraversabilityGrid& u,
	    const GoalLayer& goals, const CellIndex& start);
	/** extractPath for a caller that checked the inputs (checkStart and a
	 * traversable goal): no pass over the grid. Throws NoPathError,
	 * PlanningError. */
	static PlannedPath tracePath(
	    const DiffusionField& field, const TraversabilityGrid& u,
	    const GoalLayer& goals, const CellIndex& start);

	/** checkInputs + computeField + extractPath; the field is stored in
	 * `field` when not null. */
	PlannedPath plan(
	    const TraversabilityGrid& u, const GoalLayer& goals,
	    const CellIndex& start, DiffusionField* field = nullptr) const;
	/** As above from world coordinates (m). */
	PlannedPath plan(
	    const TraversabilityGrid& u, const GoalLayer& goals, double startX,
	    double startY, DiffusionField* field = nullptr) const;

private:
	/** repairField, bounded by `start` into `pending` when not null. */
	FieldRepairStats repair(
	    DiffusionField& field, const TraversabilityGrid& oldU,
	    const GoalLayer& oldGoals, const TraversabilityGrid& newU,
	    const GoalLayer& newGoals, const CellRect* changed,
	    double maxWorkFraction, const CellIndex* start,
	    PendingRepair* pending) const;

	TOptions m_options;
};

}  // namespace semnav
