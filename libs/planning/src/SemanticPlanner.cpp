/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/ClassRegistry.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/planning/SemanticPlanner.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <set>

#include "PlanCache.h"

namespace semnav
{
using detail::GoalCells;
using detail::GoalKey;
using detail::owned;

namespace
{
/** "objects: door 1, washbasin 3" (or "objects: none"). */
std::string objectList(const SemanticMap& map)
{
	std::string known;
	for (const auto& o : map.instances())
		known += (known.empty() ? "" : ", ") + labelName(o.label) + " " +
		         std::to_string(o.id);
	return "objects: " + (known.empty() ? std::string("none") : known);
}

/** A point goal must lie on the map: say where the map is. */
void checkGoalOnMap(const GridGeometry& g, double x, double y)
{
	if (g.cellOf(x, y)) return;
	char buf[200];
	std::snprintf(
	    buf, sizeof(buf),
	    "goal (%.3f, %.3f) is outside the map [%.3f, %.3f] x [%.3f, %.3f]", x,
	    y, g.originX, g.maxX(), g.originY, g.maxY());
	throw PlanningError(buf);
}

/** Bounding box of the cells in exactly one of two sorted lists. */
CellRect differingCells(
    const std::vector<std::size_t>& a, const std::vector<std::size_t>& b,
    const GridGeometry& g)
{
	std::vector<std::size_t> d;
	std::set_symmetric_difference(
	    a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(d));
	CellRect r;
	for (const std::size_t i : d)
	{
		const CellIndex c = g.cellAt(i);
		r.add(c.row, c.col);
	}
	return r;
}

/** Turns `layer`, holding the goal cells `from`, into `to`; returns the
 * cells that changed. */
CellRect applyGoalChange(
    const GoalCells& from, const GoalCells& to, GoalLayer& layer)
{
	const GridGeometry& g = layer.geometry();
	CellRect r;
	const auto set = [&](std::size_t i, int id)
	{
		layer.setId(i, id);
		const CellIndex c = g.cellAt(i);
		r.add(c.row, c.col);
	};
	std::size_t a = 0, b = 0;
	while (a < from.size() || b < to.size())
	{
		if (b == to.size() || (a < from.size() && from[a].first < to[b].first))
			set(from[a++].first, 0);
		else if (a == from.size() || to[b].first < from[a].first)
		{
			set(to[b].first, to[b].second);
			b++;
		}
		else
		{
			if (from[a].second != to[b].second) set(to[b].first, to[b].second);
			a++;
			b++;
		}
	}
	return r;
}

bool anyTraversable(const GoalCells& cells, const TraversabilityGrid& u)
{
	return std::any_of(
	    cells.begin(), cells.end(),
	    [&](const auto& c) { return !u.blocked(c.first); });
}

/** Copies the cells of `r` from one grid to another of the same geometry. */
void copyCells(
    const std::vector<double>& from, std::vector<double>& to,
    const GridGeometry& g, const CellRect& r)
{
	for (int row = r.row0; row < r.row1; row++)
		std::copy(
		    from.begin() + static_cast<long>(g.index(row, r.col0)),
		    from.begin() + static_cast<long>(g.index(row, r.col1 - 1)) + 1,
		    to.begin() + static_cast<long>(g.index(row, r.col0)));
}

/** Adds the cells of `rect` holding an object id to that id's box. */
void scanPainted(
    const SemanticMap& map, const CellRect& rect,
    std::map<int, CellRect>& painted, std::set<int>* ids = nullptr)
{
	const GridGeometry& g = map.geometry();
	const auto& objects = map.get("objects");
	const CellRect r = rect.clipped(g);
	for (int row = r.row0; row < r.row1; row++)
		for (int col = r.col0; col < r.col1; col++)
			if (const auto id = static_cast<int>(objects[g.index(row, col)]))
			{
				painted[id].add(row, col);
				if (ids) ids->insert(id);
			}
}

/** Drops the regions a map change may have reached: objects painted in the
 * changed cells, or whose cells lie within reach of them, and objects with
 * no cell (their region comes from their footprint, which any insertion
 * may move). Everything after a change of the whole map or of the reach. */
void followChanges(
    detail::ObjectRegions& r, const SemanticMap& map,
    const SemanticMap::Changes& changes, double reach)
{
	const GridGeometry& g = map.geometry();
	if (!r.valid || r.reach != reach || changes.all)
	{
		r = detail::ObjectRegions();
		r.reach = reach;
		scanPainted(map, CellRect::all(g), r.painted);
		r.valid = true;
		return;
	}
	std::set<int> repainted;
	scanPainted(map, changes.cells, r.painted, &repainted);
	const int margin = static_cast<int>(std::ceil(reach / g.resolution)) + 1;
	for (auto it = r.cells.begin(); it != r.cells.end();)
	{
		const CellRect& box = r.painted[it->first];
		if (box.empty() || repainted.count(it->first) ||
		    box.dilated(margin).intersects(changes.cells))
			it = r.cells.erase(it);
		else
			++it;
	}
}

double msSince(std::chrono::steady_clock::time_point t0)
{
	return std::chrono::duration<double, std::milli>(
	           std::chrono::steady_clock::now() - t0)
	    .count();
}
}  // namespace

SemanticPlanner::SemanticPlanner(
    const SemanticMap& map, const CnnPlanner::TOptions& cnn,
    const TraversabilityBuilder::TOptions& traversability)
    : m_map(map),
      m_cnn(cnn),
      m_builder(traversability),
      m_cache(std::make_unique<detail::PlanCache>())
{
}

SemanticPlanner::~SemanticPlanner() = default;

void SemanticPlanner::setExtraObstacles(
    std::vector<mrpt::math::TPoint2D> points)
{
	std::lock_guard<std::mutex> lock(m_mutex);
	m_extraObstacles = std::move(points);
}

void SemanticPlanner::setStartBoundedRepair(bool on)
{
	std::lock_guard<std::mutex> lock(m_mutex);
	m_startBounded = on;
}

SemanticPlanner::Counters SemanticPlanner::counters() const
{
	std::lock_guard<std::mutex> lock(m_mutex);
	return m_counters;
}

void SemanticPlanner::clearCache()
{
	std::lock_guard<std::mutex> lock(m_mutex);
	m_cache->pending.clear();
	m_cache->valid = false;
}

std::vector<std::size_t> SemanticPlanner::extraObstacleCells() const
{
	const GridGeometry& g = m_map.geometry();
	std::vector<std::size_t> cells;
	for (const auto& p : m_extraObstacles)
		if (const auto c = g.cellOf(p.x, p.y)) cells.push_back(g.index(*c));
	std::sort(cells.begin(), cells.end());
	cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
	return cells;
}

TraversabilityGrid SemanticPlanner::traversabilityIn(
    const CellRect& window, CostProfile profile,
    const std::vector<std::size_t>& extraCells) const
{
	const GridGeometry& g = m_map.geometry();
	const CellRect w = window.clipped(g);
	const int rows = w.row1 - w.row0, cols = w.col1 - w.col0;
	const GridGeometry sub =
	    rows == g.rows && cols == g.cols
	        ? g
	        : GridGeometry(
	              g.resolution, g.originX + w.col0 * g.resolution,
	              g.originY + w.row0 * g.resolution, cols, rows);
	const std::size_t n = sub.cellCount();
	const auto& cost = m_map.get("cost");
	const auto& labelLayer = m_map.get("labels");
	std::vector<float> baseU(n);
	std::vector<LabelSet> labels(n);
	std::vector<CellOccupancy> occ(n, CellOccupancy::Unknown);
	const std::vector<SemanticMap::CellState> states = m_map.cellStates(w);
	for (int r = 0; r < rows; r++)
		for (int c = 0; c < cols; c++)
		{
			const std::size_t i = g.index(w.row0 + r, w.col0 + c);
			const std::size_t k = sub.index(r, c);
			baseU[k] = cost[i];
			labels[k] = LabelSet(static_cast<LabelSet::mask_t>(labelLayer[i]));
			if (states[k] == SemanticMap::CellState::Free)
				occ[k] = CellOccupancy::Free;
			else if (states[k] == SemanticMap::CellState::Occupied)
				occ[k] = CellOccupancy::Occupied;
		}
	for (const std::size_t i : extraCells)
	{
		const CellIndex c = g.cellAt(i);
		if (w.contains(c.row, c.col))
			occ[sub.index(c.row - w.row0, c.col - w.col0)] =
			    CellOccupancy::Occupied;
	}
	// The map's cost layer already holds u_s (grass roughness, robot type,
	// objects that left); the builder adds C-space and the profile.
	return m_builder.buildFromCost(
	    sub, baseU, m_map.costModel().options().lethalCost, labels, occ,
	    profile);
}

TraversabilityGrid SemanticPlanner::traversability(CostProfile profile) const
{
	std::lock_guard<std::mutex> lock(m_mutex);
	const auto extras = extraObstacleCells();
	const auto& c = *m_cache;
	if (c.valid && c.key.profile == profile &&
	    c.u->geometry() == m_map.geometry() &&
	    m_map.changesSince(c.mapVersion).none() && c.extraCells == extras)
		return *c.u;
	return traversabilityIn(CellRect::all(m_map.geometry()), profile, extras);
}

GoalCells SemanticPlanner::goalCellsOf(const GoalKey& key) const
{
	const GridGeometry& g = m_map.geometry();
	GoalCells cells;
	if (key.kind == GoalKey::Kind::Point)
	{
		checkGoalOnMap(g, key.x, key.y);
		GoalLayer disc(g);
		disc.addDisc(key.x, key.y, m_builder.options().goalReach);
		for (std::size_t i = 0; i < g.cellCount(); i++)
			if (disc.isGoal(i)) cells.emplace_back(i, disc.id(i));
		return cells;
	}
	std::vector<int> ids;
	if (key.kind == GoalKey::Kind::Object)
		ids.push_back(key.objectId);
	else
		for (const auto& o : m_map.instances(key.label)) ids.push_back(o.id);
	auto& regions = m_cache->regions;
	const double reach = m_builder.goalRegionRadius(key.profile);
	if (!regions.valid || regions.reach != reach)
		followChanges(regions, m_map, {true, {}}, reach);
	for (const int id : ids)
	{
		auto it = regions.cells.find(id);
		if (it == regions.cells.end())
		{
			std::vector<std::size_t> region;
			for (const auto& [cx, cy] : m_map.goalRegion(id, reach))
				region.push_back(g.index(cy, cx));
			it = regions.cells.emplace(id, std::move(region)).first;
		}
		for (const std::size_t i : it->second) cells.emplace_back(i, id);
	}
	// A cell in two regions keeps the first id (GoalLayer::addCells).
	std::stable_sort(
	    cells.begin(), cells.end(),
	    [](const auto& a, const auto& b) { return a.first < b.first; });
	cells.erase(
	    std::unique(
	        cells.begin(), cells.end(),
	        [](const auto& a, const auto& b) { return a.first == b.first; }),
	    cells.end());
	return cells;
}

void SemanticPlanner::rebuild(
    const GoalKey& key, std::vector<std::size_t> extraCells,
    const CellIndex& start) const
{
	auto& c = *m_cache;
	const GridGeometry& g = m_map.geometry();
	c.pending.clear();
	c.valid = false;
	c.mapVersion = m_map.version();
	c.regions.valid = false;
	c.u = std::make_shared<TraversabilityGrid>(
	    traversabilityIn(CellRect::all(g), key.profile, extraCells));
	m_counters.fullTraversability++;
	c.goalCells = goalCellsOf(key);
	c.goals = std::make_shared<GoalLayer>(g);
	for (const auto& [i, id] : c.goalCells) c.goals->setId(i, id);
	if (!anyTraversable(c.goalCells, *c.u))
		CnnPlanner::checkInputs(*c.u, *c.goals, start);  // throws
	m_cnn.computeFieldInto(*c.u, *c.goals, owned(c.field));
	m_counters.fullFields++;
	m_counters.last = FieldUpdate::Full;
	c.spareU = std::make_shared<TraversabilityGrid>(*c.u);
	c.spareGoals = std::make_shared<GoalLayer>(*c.goals);
	c.extraCells = std::move(extraCells);
	c.key = key;
	c.valid = true;
}

CellRect SemanticPlanner::updateTraversability(
    const CellRect& inputs, CostProfile profile,
    const std::vector<std::size_t>& extraCells) const
{
	auto& c = *m_cache;
	const GridGeometry& g = m_map.geometry();
	if (inputs.empty()) return {};
	const int reach = m_builder.reachCells(profile, g.resolution);
	const CellRect changed = inputs.dilated(reach).clipped(g);
	const CellRect window = inputs.dilated(2 * reach + 1).clipped(g);
	const auto area = static_cast<std::size_t>(window.row1 - window.row0) *
	                  static_cast<std::size_t>(window.col1 - window.col0);
	if (2 * area > g.cellCount())
	{
		c.spareU = std::make_shared<TraversabilityGrid>(
		    traversabilityIn(CellRect::all(g), profile, extraCells));
		m_counters.fullTraversability++;
		return CellRect::all(g);
	}
	const TraversabilityGrid sub =
	    traversabilityIn(window, profile, extraCells);
	m_counters.partialTraversability++;
	const GridGeometry& s = sub.geometry();
	auto& u = owned(c.spareU).values();
	for (int row = changed.row0; row < changed.row1; row++)
	{
		const auto from = sub.values().begin() +
		                  static_cast<long>(s.index(
		                      row - window.row0, changed.col0 - window.col0));
		std::copy(
		    from, from + (changed.col1 - changed.col0),
		    u.begin() + static_cast<long>(g.index(row, changed.col0)));
	}
	return changed;
}

void SemanticPlanner::updateField(
    bool sameGoal, const CellRect& changed, const CellIndex& start) const
{
	auto& c = *m_cache;
	if (!sameGoal)
	{
		m_cnn.computeFieldInto(*c.spareU, *c.spareGoals, owned(c.field));
		m_counters.fullFields++;
		m_counters.last = FieldUpdate::Full;
		return;
	}
	if (changed.empty())
	{
		m_counters.reuses++;
		m_counters.last = FieldUpdate::Reuse;
		return;
	}
	const FieldRepairStats st =
	    m_startBounded ? m_cnn.repairFieldFrom(
	                         start, owned(c.field), *c.u, *c.goals, *c.spareU,
	                         *c.spareGoals, c.pending, &changed)
	                   : m_cnn.repairField(
	                         owned(c.field), *c.u, *c.goals, *c.spareU,
	                         *c.spareGoals, &changed);
	m_counters.boundedRepairs += !c.pending.empty();
	m_counters.changedCells += st.changedCells;
	m_counters.repairedCells += st.poppedCells;
	if (st.fullRecompute) m_counters.repairFallbacks++;
	(st.fullRecompute ? m_counters.fullFields : m_counters.repairs)++;
	m_counters.last =
	    st.fullRecompute ? FieldUpdate::Full : FieldUpdate::Repair;
}

void SemanticPlanner::refresh(const GoalKey& key, const CellIndex& start) const
{
	auto& c = *m_cache;
	const GridGeometry& g = m_map.geometry();
	auto extras = extraObstacleCells();
	if (!c.valid || !(c.u->geometry() == g) || c.key.profile != key.profile)
		return rebuild(key, std::move(extras), start);
	const std::uint64_t version = m_map.version();
	const SemanticMap::Changes changes = m_map.changesSince(c.mapVersion);
	const CellRect inputs =
	    (changes.all ? CellRect::all(g) : changes.cells)
	        .united(differingCells(c.extraCells, extras, g));
	if (version != c.mapVersion && c.regions.valid)
		followChanges(
		    c.regions, m_map, changes, m_builder.goalRegionRadius(key.profile));
	const bool sameGoal = c.key == key;
	// Object goals follow every version: an instance may become reported
	// (or its footprint move) with no cell changed.
	const bool goalsMayChange =
	    !sameGoal ||
	    (key.kind != GoalKey::Kind::Point && version != c.mapVersion);
	if (inputs.empty() && !goalsMayChange)
	{
		c.mapVersion = version;
		m_counters.reuses++;
		m_counters.last = FieldUpdate::Reuse;
		finishPending(&start);  // nothing when the start is the same
		return;
	}
	// Pending work refers to u and goals: done before they change (or
	// dropped with a field computed anew).
	if (sameGoal)
		finishPending(nullptr);
	else
		c.pending.clear();
	// Any exception leaves the spares half updated: the cache is dropped.
	c.valid = false;
	const CellRect uRect = updateTraversability(inputs, key.profile, extras);
	GoalCells cells = goalsMayChange ? goalCellsOf(key) : c.goalCells;
	const CellRect goalRect =
	    applyGoalChange(c.goalCells, cells, owned(c.spareGoals));
	if (!anyTraversable(cells, *c.spareU))
		CnnPlanner::checkInputs(*c.spareU, *c.spareGoals, start);  // throws
	updateField(sameGoal, uRect.united(goalRect), start);
	c.valid = true;
	// The new inputs become the cache's; the spares catch up.
	std::swap(c.u, c.spareU);
	std::swap(c.goals, c.spareGoals);
	copyCells(c.u->values(), owned(c.spareU).values(), g, uRect);
	applyGoalChange(c.goalCells, cells, owned(c.spareGoals));
	c.goalCells = std::move(cells);
	c.extraCells = std::move(extras);
	c.key = key;
	c.mapVersion = version;
}

SemanticPlanner::SharedPlan SemanticPlanner::run(
    double x, double y, const GoalKey& key, bool complete) const
{
	std::lock_guard<std::mutex> lock(m_mutex);
	const auto t0 = std::chrono::steady_clock::now();
	SharedPlan p;
	p.start = CnnPlanner::startCell(m_map.geometry(), x, y);
	refresh(key, p.start);
	if (complete) finishPending(nullptr);
	m_counters.lastMilliseconds = msSince(t0);
	const auto& c = *m_cache;
	CnnPlanner::checkStart(*c.u, p.start);
	p.path = CnnPlanner::tracePath(*c.field, *c.u, *c.goals, p.start);
	p.field = c.field;
	p.u = c.u;
	p.goals = c.goals;
	p.goalLabel = key.kind == GoalKey::Kind::Point ? Label::Unknown : key.label;
	p.goalObjectId = p.goalLabel == Label::Unknown ? 0 : p.path.goalId;
	p.fieldComplete = c.pending.empty();
	return p;
}

void SemanticPlanner::finishPending(const CellIndex* start) const
{
	auto& c = *m_cache;
	if (c.pending.empty()) return;
	const FieldRepairStats st =
	    m_cnn.finishRepair(owned(c.field), c.pending, start);
	m_counters.repairedCells += st.poppedCells;
	m_counters.pendingFinished += c.pending.empty();
}

SemanticPlanner::Plan SemanticPlanner::SharedPlan::copy() const
{
	Plan p;
	p.path = path;
	p.field = *field;
	p.u = *u;
	p.goals = *goals;
	p.start = start;
	p.goalLabel = goalLabel;
	p.goalObjectId = goalObjectId;
	return p;
}

SemanticPlanner::Plan SemanticPlanner::toLabel(
    double x, double y, Label label, CostProfile profile) const
{
	return run(x, y, labelKey(label, profile), true).copy();
}

SemanticPlanner::Plan SemanticPlanner::toObject(
    double x, double y, int objectId, CostProfile profile) const
{
	return run(x, y, objectKey(objectId, profile), true).copy();
}

SemanticPlanner::Plan SemanticPlanner::toPoint(
    double x, double y, double gx, double gy, CostProfile profile) const
{
	return run(x, y, pointKey(gx, gy, profile), true).copy();
}

SemanticPlanner::SharedPlan SemanticPlanner::toLabelShared(
    double x, double y, Label label, CostProfile profile) const
{
	return run(x, y, labelKey(label, profile));
}

SemanticPlanner::SharedPlan SemanticPlanner::toObjectShared(
    double x, double y, int objectId, CostProfile profile) const
{
	return run(x, y, objectKey(objectId, profile));
}

SemanticPlanner::SharedPlan SemanticPlanner::toPointShared(
    double x, double y, double gx, double gy, CostProfile profile) const
{
	return run(x, y, pointKey(gx, gy, profile));
}

GoalKey SemanticPlanner::labelKey(Label label, CostProfile profile) const
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
	if (m_map.instances(label).empty())
		throw NoInstanceError(
		    "the map has no " + labelName(label) + " (" + objectList(m_map) +
		    ")");
	GoalKey key;
	key.kind = GoalKey::Kind::Label;
	key.label = label;
	key.profile = profile;
	return key;
}

GoalKey SemanticPlanner::objectKey(int objectId, CostProfile profile) const
{
	GoalKey key;
	key.kind = GoalKey::Kind::Object;
	// The objects of the map are those it reports (SemanticMap::reported):
	// a candidate seen too seldom or of implausible size is no goal.
	const ObjectInstance* o = m_map.object(objectId);
	if (!o)
		throw NoInstanceError(
		    "the map has no object " + std::to_string(objectId) + " (" +
		    objectList(m_map) + ")");
	key.label = o->label;
	key.objectId = objectId;
	key.profile = profile;
	return key;
}

GoalKey SemanticPlanner::pointKey(
    double gx, double gy, CostProfile profile) const
{
	checkGoalOnMap(m_map.geometry(), gx, gy);
	GoalKey key;
	key.kind = GoalKey::Kind::Point;
	key.x = gx;
	key.y = gy;
	key.profile = profile;
	return key;
}

}  // namespace semnav
