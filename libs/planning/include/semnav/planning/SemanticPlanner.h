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

namespace semnav
{
class SemanticMap;

/** The map has no (reported) instance of the requested label. */
class NoInstanceError : public PlanningError
{
	using PlanningError::PlanningError;
};

/** Adapter from a SemanticMap to the CNN planner: u from the map's
 * travel-cost layer, labels and occupancy (TraversabilityBuilder::
 * buildFromCost), goals from the map's objects. "Go to the nearest
 * <label>" puts the goal regions of every instance of the label in one goal
 * layer, so the diffusion picks the least expensive one by itself. */
class SemanticPlanner
{
public:
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

	SemanticPlanner(
	    const SemanticMap& map, const CnnPlanner::TOptions& cnn,
	    const TraversabilityBuilder::TOptions& traversability);

	/** Least-cost path from (x, y) to any instance of `label`, a goal
	 * class of the ClassRegistry. Throws NoInstanceError (also for a class
	 * that is no goal), StartOutsideMapError, StartBlockedError,
	 * EmptyGoalError, NoPathError. */
	Plan toLabel(double x, double y, Label label, CostProfile profile) const;
	/** Path to a given object of the map. */
	Plan toObject(double x, double y, int objectId, CostProfile profile) const;
	/** Path to the cells within goal_reach_m of (gx, gy). */
	Plan toPoint(
	    double x, double y, double gx, double gy, CostProfile profile) const;

	/** Obstacles the map does not hold (e.g. sensed by the robot while
	 * driving), world frame: their cells count as occupied (inflated like
	 * map obstacles) in every later plan. */
	void setExtraObstacles(std::vector<mrpt::math::TPoint2D> points)
	{
		m_extraObstacles = std::move(points);
	}
	const std::vector<mrpt::math::TPoint2D>& extraObstacles() const
	{
		return m_extraObstacles;
	}

	/** u of the whole map for a profile. */
	TraversabilityGrid traversability(CostProfile profile) const;

private:
	Plan run(
	    double x, double y, TraversabilityGrid u, GoalLayer goals,
	    Label label) const;
	GoalLayer goalsOf(
	    const std::vector<int>& objectIds, CostProfile profile) const;

	const SemanticMap& m_map;
	CnnPlanner m_cnn;
	TraversabilityBuilder m_builder;
	std::vector<mrpt::math::TPoint2D> m_extraObstacles;
};

}  // namespace semnav
