/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/ClassRegistry.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/planning/SemanticPlanner.h>

namespace semnav
{
SemanticPlanner::SemanticPlanner(
    const SemanticMap& map, const CnnPlanner::TOptions& cnn,
    const TraversabilityBuilder::TOptions& traversability)
    : m_map(map), m_cnn(cnn), m_builder(traversability)
{
}

TraversabilityGrid SemanticPlanner::traversability(CostProfile profile) const
{
	const GridGeometry& g = m_map.geometry();
	std::vector<LabelSet> labels(g.cellCount());
	std::vector<CellOccupancy> occ(g.cellCount(), CellOccupancy::Unknown);
	for (int row = 0; row < g.rows; row++)
		for (int col = 0; col < g.cols; col++)
		{
			const std::size_t i = g.index(row, col);
			labels[i] = m_map.labels(col, row);
			switch (m_map.cellState(col, row))
			{
				case SemanticMap::CellState::Free:
					occ[i] = CellOccupancy::Free;
					break;
				case SemanticMap::CellState::Occupied:
					occ[i] = CellOccupancy::Occupied;
					break;
				default:
					break;
			}
		}
	for (const auto& p : m_extraObstacles)
		if (const auto c = g.cellOf(p.x, p.y))
			occ[g.index(*c)] = CellOccupancy::Occupied;
	// The map's cost layer already holds u_s (grass roughness, robot type,
	// objects that left); the builder adds C-space and the profile.
	return m_builder.buildFromCost(
	    g, m_map.get("cost"), m_map.costModel().options().lethalCost, labels,
	    occ, profile);
}

GoalLayer SemanticPlanner::goalsOf(
    const std::vector<int>& objectIds, CostProfile profile) const
{
	GoalLayer goals(m_map.geometry());
	const double reach = m_builder.goalRegionRadius(profile);
	for (int id : objectIds)
	{
		std::vector<CellIndex> cells;
		for (const auto& [cx, cy] : m_map.goalRegion(id, reach))
			cells.push_back({cy, cx});
		goals.addCells(cells, id);
	}
	return goals;
}

SemanticPlanner::Plan SemanticPlanner::toLabel(
    double x, double y, Label label, CostProfile profile) const
{
	if (!classInfo(label).goal)
	{
		std::string goals;
		for (Label l : allLabels())
			if (classInfo(l).goal)
				goals += (goals.empty() ? "" : ", ") + labelName(l);
		throw NoInstanceError(
		    labelName(label) + " is no goal class (goals: " + goals + ")");
	}
	const auto objs = m_map.instances(label);
	if (objs.empty())
	{
		std::string known;
		for (const auto& o : m_map.instances())
			known += (known.empty() ? "" : ", ") + labelName(o.label) + " " +
			         std::to_string(o.id);
		throw NoInstanceError(
		    "the map has no " + labelName(label) +
		    " (objects: " + (known.empty() ? "none" : known) + ")");
	}
	std::vector<int> ids;
	for (const auto& o : objs) ids.push_back(o.id);
	return run(x, y, traversability(profile), goalsOf(ids, profile), label);
}

SemanticPlanner::Plan SemanticPlanner::toObject(
    double x, double y, int objectId, CostProfile profile) const
{
	const Label label = m_map.instance(objectId).label;
	return run(
	    x, y, traversability(profile), goalsOf({objectId}, profile), label);
}

SemanticPlanner::Plan SemanticPlanner::toPoint(
    double x, double y, double gx, double gy, CostProfile profile) const
{
	GoalLayer goals(m_map.geometry());
	if (!m_map.geometry().cellOf(gx, gy))
		throw PlanningError(
		    "goal (" + std::to_string(gx) + ", " + std::to_string(gy) +
		    ") is outside the map");
	goals.addDisc(gx, gy, m_builder.options().goalReach);
	return run(x, y, traversability(profile), std::move(goals), Label::Unknown);
}

SemanticPlanner::Plan SemanticPlanner::run(
    double x, double y, TraversabilityGrid u, GoalLayer goals,
    Label label) const
{
	Plan p;
	p.start = CnnPlanner::startCell(u.geometry(), x, y);
	p.path = m_cnn.plan(u, goals, p.start, &p.field);
	p.u = std::move(u);
	p.goals = std::move(goals);
	p.goalLabel = label;
	p.goalObjectId = label == Label::Unknown ? 0 : p.path.goalId;
	return p;
}

}  // namespace semnav
