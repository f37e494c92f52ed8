/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/poses/CPose3D.h>
#include <octomap/OcTree.h>
#include <semnav/common/Error.h>
#include <semnav/common/OptionTable.h>
#include <semnav/map/SemanticMap.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace semnav
{
const char* const SemanticMap::kLabels = "labels";
const char* const SemanticMap::kCost = "cost";
const char* const SemanticMap::kObjects = "objects";
const char* const SemanticMap::kRoughness = "roughness";
const char* const SemanticMap::kObservations = "observations";
const char* const SemanticMap::kStairsSweeps = "stairs_sweeps";

namespace
{
using O = SemanticMap::TOptions;
const OptionTable<O>& optionTable()
{
	static const auto t =
	    OptionTable<O>()
	        .real(
	            "resolution_m", &O::resolution, 0.005, 1.0,
	            "Cell size (the paper: 5 cm).")
	        .real(
	            "grow_margin_m", &O::growMargin, 0, 100,
	            "Room added around new points when the map grows.")
	        .real(
	            "obstacle_min_height_m", &O::obstacleMinHeight, 0, 1.0,
	            "Points from floor + this height...")
	        .real(
	            "robot_height_m", &O::robotHeight, &O::obstacleMinHeight, 10,
	            "...up to this height are obstacles.")
	        .real(
	            "robot_radius_m", &O::robotRadius, 0, 5,
	            "The cells the robot stands on are marked free.")
	        .real(
	            "hit_probability", &O::hitProbability, 0.5, 0.99,
	            "Occupancy update of a cell hit in a sweep.")
	        .real(
	            "free_probability", &O::freeProbability, 0.01, 0.5,
	            "Occupancy update of a cell seen free in a sweep.")
	        .real(
	            "occupied_threshold", &O::occupiedThreshold, 0.5, 1,
	            "Occupied above this occupancy (also map.yaml's).")
	        .real(
	            "free_threshold", &O::freeThreshold, 0, 0.5,
	            "Free below this occupancy (also map.yaml's).")
	        .real(
	            "merge_distance_m", &O::mergeDistance, 0.01, 10,
	            "Doors and stairs closer than this (or overlapping) are one "
	            "object.")
	        .real(
	            "object_merge_distance_m", &O::objectMergeDistance, 0.01, 10,
	            "Washbasins and wastebaskets join an instance only this "
	            "close to one of its detections.")
	        .integer(
	            "min_observations", &O::minObservations, 1, 1000,
	            "Cascade objects seen in fewer sweeps are not reported.")
	        .integer(
	            "door_min_observations", &O::doorMinObservations, 1, 1000,
	            "Doors seen in fewer sweeps are not reported.")
	        .real(
	            "door_min_detection_ratio", &O::doorMinDetectionRatio, 0, 1,
	            "Doors detected in a smaller share of the sweeps that had "
	            "their place in view are not reported (0: no check).")
	        .real(
	            "door_sure_min_width_m", &O::doorSureMinWidth, 0, 10,
	            "A door is sure when a sighting showed a whole leaf this "
	            "wide...")
	        .real(
	            "door_sure_min_height_m", &O::doorSureMinHeight, 0, 10,
	            "...and this high...")
	        .real(
	            "door_sure_max_incidence_deg", &O::doorSureMaxIncidenceDeg, 0,
	            90, "...seen at most this far from straight on.")
	        .real(
	            "door_sure_min_detection_ratio", &O::doorSureMinDetectionRatio,
	            0, 1, "Sure doors need only this detection ratio.")
	        .real(
	            "door_view_min_visible_share", &O::doorViewMinVisibleShare, 0,
	            1,
	            "A sweep has a door in view when this share of its face is "
	            "in the field of view and unhidden...")
	        .real(
	            "door_view_max_bearing_deg", &O::doorViewMaxBearingDeg, 0, 180,
	            "...within this bearing of the robot's heading...")
	        .real(
	            "door_view_max_incidence_deg", &O::doorViewMaxIncidenceDeg, 0,
	            90, "...at most this far from straight on...")
	        .integer(
	            "door_view_min_pixels", &O::doorViewMinPixels, 0, 1000000,
	            "...where the door would cover this many pixels.")
	        .integer(
	            "door_view_history", &O::doorViewHistory, 0, 10000,
	            "Sweeps kept to count the views of a door before its first "
	            "detection.")
	        .real(
	            "min_detection_ratio", &O::minDetectionRatio, 0, 1,
	            "Cascade objects detected in a smaller share of the sweeps "
	            "that saw them are not reported.")
	        .real(
	            "stairs_min_detection_ratio", &O::stairsMinDetectionRatio, 0, 1,
	            "The same for stairs.")
	        .real(
	            "sure_shape_score", &O::sureShapeScore, 0, 1,
	            "An object is sure when a detection scored this on its 3D "
	            "shape check.")
	        .real(
	            "sure_min_detection_ratio", &O::sureMinDetectionRatio, 0, 1,
	            "Sure objects need only this detection ratio.")
	        .integer(
	            "unsure_min_observations", &O::unsureMinObservations, 1, 1000,
	            "Objects that are not sure need this many "
	            "detections.")
	        .real(
	            "unsure_once_min_shape_score", &O::unsureOnceMinShapeScore, 0,
	            1,
	            "Objects not sure scoring at least this need only "
	            "min_observations detections (0: none).")
	        .real(
	            "unsure_stairs_min_width_m", &O::unsureStairsMinWidth, 0, 10,
	            "Stairs not sure whose typical detection is narrower are not "
	            "reported (0: no check).")
	        .real(
	            "unsure_wastebasket_max_width_m", &O::unsureWastebasketMaxWidth,
	            0, 10,
	            "Wastebaskets not sure never seen narrower are not reported "
	            "(0: no check).")
	        .real(
	            "unsure_wastebasket_wide_min_shape_score",
	            &O::unsureWastebasketWideMinShapeScore, 0, 1,
	            "...unless their shape check scored at least this (0: no "
	            "exception).")
	        .real(
	            "unsure_other_label_distance_m", &O::unsureOtherLabelDistance,
	            0, 10,
	            "Objects not sure this close to a sure object of another "
	            "label are not reported (0: no check).")
	        .integer(
	            "view_min_pixels", &O::viewMinPixels, 0, 1000000,
	            "A sweep sees an object in line of sight that would "
	            "cover this many pixels...")
	        .real(
	            "view_max_bearing_deg", &O::viewMaxBearingDeg, 0, 180,
	            "...within this bearing of the robot's heading.")
	        .real(
	            "washbasin_min_top_m", &O::washbasinMinTop, 0, 3,
	            "Washbasins never reaching this height are not reported.")
	        .real(
	            "washbasin_max_wall_distance_m", &O::washbasinMaxWallDistance,
	            0, 5,
	            "Washbasins without a wall this close are not reported "
	            "(0: no check).")
	        .real(
	            "stairs_max_bottom_m", &O::stairsMaxBottom, 0, 3,
	            "Stairs never coming down to this height are not reported.")
	        .real(
	            "sure_stairs_max_bottom_m", &O::sureStairsMaxBottom, 0, 3,
	            "Sure stairs need only come down to this height (0: "
	            "stairs_max_bottom_m).")
	        .flag(
	            "stairs_centroid_from_cells", &O::stairsCentroidFromCells,
	            "A staircase's centroid is that of its stairs cells.")
	        .real(
	            "stairs_min_cell_share", &O::stairsMinCellShare, 0, 1,
	            "Only cells labelled stairs in this share of the flight's "
	            "sweeps (0: all).")
	        .real(
	            "stairs_cell_margin_m", &O::stairsCellMargin, 0, 5,
	            "A staircase's cells count up to this far outside its "
	            "footprint (0: inside it).")
	        .real(
	            "stairs_cell_gap_m", &O::stairsCellGap, 0, 2,
	            "Cells of a flight this close are connected (at most one "
	            "cell: 8-connected).")
	        .real(
	            "stairs_riser_gap_m", &O::stairsRiserGap, 0, 2,
	            "Cells of a flight this far apart across its risers are "
	            "connected (0: off).")
	        .real(
	            "stairs_riser_min_row_m", &O::stairsRiserMinRow, 0, 5,
	            "The riser gap joins only a row of cells this long along the "
	            "risers.")
	        .flag(
	            "door_sighting_largest_region", &O::doorSightingLargestRegion,
	            "A sweep's sighting of a door is its largest door region "
	            "there (false: the first).")
	        .real(
	            "door_sighting_box_centre_min_width_m",
	            &O::doorSightingBoxCentreMinWidth, 0, 10,
	            "A door region at least this wide is sighted at the middle of "
	            "its box, not the mean of its points (0: never).")
	        .real(
	            "door_sighting_box_centre_max_width_m",
	            &O::doorSightingBoxCentreMaxWidth, 0, 10,
	            "...and at most this wide (0: no limit).")
	        .real(
	            "door_sighting_full_height_share",
	            &O::doorSightingFullHeightShare, 0, 1,
	            "...at the middle of its columns spanning this share of its "
	            "height (0: of its box).")
	        .real(
	            "door_region_max_height_m", &O::doorRegionMaxHeight, 0, 10,
	            "Higher door regions make and join no door (0: no limit).")
	        .flag(
	            "door_footprint_from_points", &O::doorFootprintFromPoints,
	            "A door region's footprint is the world box of its points "
	            "(false: the box around its robot-frame box).")
	        .real(
	            "door_min_height_m", &O::doorMinHeight, 0, 10,
	            "Lower doors are not reported.")
	        .real(
	            "door_min_width_m", &O::doorMinWidth, 0, 10,
	            "Doors none of whose sightings is this wide are not reported "
	            "(0: no check).")
	        .real(
	            "double_door_max_width_m", &O::doubleDoorMaxWidth, 0, 10,
	            "Two doors side by side in one wall, together at most this "
	            "wide, are the leaves of one double door (0: no join)...")
	        .real(
	            "double_door_max_leaf_width_m", &O::doubleDoorMaxLeafWidth, 0,
	            10, "...each at most this wide...")
	        .real(
	            "double_door_max_plane_offset_m", &O::doubleDoorMaxPlaneOffset,
	            0, 1, "...at most this far from one plane...")
	        .real(
	            "double_door_max_wall_m", &O::doubleDoorMaxWall, 0, 10,
	            "...with no longer stretch of wall between them...")
	        .real(
	            "double_door_min_leaf_width_ratio",
	            &O::doubleDoorMinLeafWidthRatio, 0, 1,
	            "...the narrower leaf at least this share of the wider (0: no "
	            "check)...")
	        .real(
	            "double_door_max_leaf_offset_m", &O::doubleDoorMaxLeafOffset, 0,
	            1,
	            "...and the leaves at most this far from one plane (0: "
	            "double_door_max_plane_offset_m only).")
	        .real(
	            "door_join_distance_m", &O::doorJoinDistance, 0, 5,
	            "Two doors in one wall this close, footprints overlapping, "
	            "are one door found twice (0: no join).")
	        .real(
	            "door_join_contained_share", &O::doorJoinContainedShare, 0, 1,
	            "A door seen no more often whose footprint lies this share "
	            "inside another's in its wall is a piece of it (0: no join).")
	        .real(
	            "door_centroid_max_weight_width_m",
	            &O::doorCentroidMaxWeightWidth, 0, 10,
	            "A door's centroid weighs its sightings by their width "
	            "squared, up to this width (0: plain mean).")
	        .flag(
	            "octomap", &O::octomap,
	            "Put every point into the OctoMap (octomap.bt).");
	return t;
}
}  // namespace

SEMNAV_OPTIONS_FROM_TABLE(SemanticMap::TOptions, optionTable())

SemanticMap::SemanticMap() : SemanticMap(TOptions()) {}

SemanticMap::SemanticMap(const TOptions& options)
    : mrpt::system::COutputLogger("SemanticMap"),
      m_options(options),
      m_costModel(options.cost),
      m_octree(std::make_unique<octomap::OcTree>(options.resolution))
{
	m_geometry.resolution = options.resolution;
	m_occupancy.setSize(
	    0, static_cast<float>(options.resolution), 0,
	    static_cast<float>(options.resolution),
	    static_cast<float>(options.resolution));
	add(kLabels, 0);
	add(kCost, static_cast<float>(m_costModel.options().unknownCost));
	add(kObjects, 0);
	add(kRoughness, std::numeric_limits<float>::quiet_NaN());
	add(kObservations, 0);
	add(kStairsSweeps, 0);
}

SemanticMap::~SemanticMap() = default;

bool SemanticMap::exists(const std::string& layer) const
{
	return m_layers.count(layer) > 0;
}

void SemanticMap::add(const std::string& layer, float value)
{
	if (!exists(layer))
		m_layers[layer] = std::vector<float>(m_geometry.cellCount(), value);
}

const std::vector<float>& SemanticMap::get(const std::string& layer) const
{
	const auto it = m_layers.find(layer);
	if (it == m_layers.end())
		throw Error("semantic map has no layer '" + layer + "'");
	return it->second;
}

std::vector<float>& SemanticMap::get(const std::string& layer)
{
	auto& v = const_cast<std::vector<float>&>(
	    static_cast<const SemanticMap*>(this)->get(layer));
	markAllChanged();
	return v;
}

std::vector<float>& SemanticMap::layer(const char* name)
{
	return const_cast<std::vector<float>&>(
	    static_cast<const SemanticMap*>(this)->get(name));
}

SemanticMap::Changes SemanticMap::changesSince(std::uint64_t version) const
{
	Changes c;
	if (version > m_version || version < m_historyStart)
	{
		c.all = true;
		return c;
	}
	for (auto it = m_changes.rbegin();
	     it != m_changes.rend() && it->version > version; ++it)
	{
		if (it->all)
		{
			c.all = true;
			return c;
		}
		c.cells = c.cells.united(it->cells);
		c.touched = c.touched.united(it->touched);
	}
	c.cells = c.cells.clipped(m_geometry);
	if (c.cells.empty()) c.cells = CellRect();
	c.touched = c.touched.united(c.cells).clipped(m_geometry);
	if (c.touched.empty()) c.touched = CellRect();
	return c;
}

void SemanticMap::markChanged(const CellRect& cells)
{
	markChanged(cells, cells);
}

void SemanticMap::markChanged(const CellRect& cells, const CellRect& touched)
{
	m_changes.push_back({++m_version, false, cells, touched});
	while (m_changes.size() > kChangeHistory)
	{
		m_historyStart = m_changes.front().version;
		m_changes.pop_front();
	}
}

void SemanticMap::markAllChanged()
{
	m_costsCurrent = false;
	// Repeated writes through accessors share one entry.
	if (!m_changes.empty() && m_changes.back().all)
	{
		m_changes.back().version = ++m_version;
		return;
	}
	markChanged(CellRect());
	m_changes.back().all = true;
}

std::vector<std::string> SemanticMap::layers() const
{
	std::vector<std::string> out;
	for (const auto& kv : m_layers) out.push_back(kv.first);
	return out;
}

LabelSet SemanticMap::labels(int cx, int cy) const
{
	return LabelSet(static_cast<LabelSet::mask_t>(at(kLabels, cx, cy)));
}

double SemanticMap::occupancy(int cx, int cy) const
{
	return m_occupancy.getCell(cx, cy);
}

SemanticMap::CellState SemanticMap::cellState(int cx, int cy) const
{
	return stateOf(at(kObservations, cx, cy), cx, cy);
}

std::vector<SemanticMap::CellState> SemanticMap::cellStates(
    const CellRect& cells) const
{
	const CellRect r = cells.clipped(m_geometry);
	std::vector<CellState> out;
	if (r.empty()) return out;
	out.reserve(static_cast<std::size_t>(r.row1 - r.row0) * (r.col1 - r.col0));
	const auto& observations = get(kObservations);
	for (int cy = r.row0; cy < r.row1; cy++)
		for (int cx = r.col0; cx < r.col1; cx++)
			out.push_back(
			    stateOf(observations[m_geometry.index(cy, cx)], cx, cy));
	return out;
}

SemanticMap::CellState SemanticMap::stateOf(
    float observations, int cx, int cy) const
{
	if (observations <= 0) return CellState::Unknown;
	const double p = occupancy(cx, cy);
	if (p >= m_options.occupiedThreshold) return CellState::Occupied;
	if (p <= m_options.freeThreshold) return CellState::Free;
	return CellState::Unknown;
}

void SemanticMap::growToInclude(
    double xmin, double ymin, double xmax, double ymax)
{
	const double res = m_geometry.resolution;
	const GridGeometry& old = m_geometry;
	const bool empty = old.cellCount() == 0;
	if (!empty && xmin >= old.originX && ymin >= old.originY &&
	    xmax < old.maxX() && ymax < old.maxY())
		return;
	const double m = m_options.growMargin;
	// Cell-aligned bounds: origins stay integer multiples of the resolution.
	auto lo = [&](double v, double cur, bool has)
	{
		const double want = std::floor((v - m) / res);
		return has ? std::min(want, std::round(cur / res)) : want;
	};
	auto hi = [&](double v, double cur, bool has)
	{
		const double want = std::ceil((v + m) / res);
		return has ? std::max(want, std::round(cur / res)) : want;
	};
	const double x0 = lo(xmin, old.originX, !empty),
	             y0 = lo(ymin, old.originY, !empty),
	             x1 = hi(xmax, old.maxX(), !empty),
	             y1 = hi(ymax, old.maxY(), !empty);
	GridGeometry g;
	g.resolution = res;
	g.originX = x0 * res;
	g.originY = y0 * res;
	g.cols = static_cast<int>(x1 - x0);
	g.rows = static_cast<int>(y1 - y0);
	const int dx =
	    empty ? 0
	          : static_cast<int>(std::round((old.originX - g.originX) / res));
	const int dy =
	    empty ? 0
	          : static_cast<int>(std::round((old.originY - g.originY) / res));

	for (auto& kv : m_layers)
	{
		const float fill =
		    kv.first == kCost
		        ? static_cast<float>(m_costModel.options().unknownCost)
		    : kv.first == kRoughness ? std::numeric_limits<float>::quiet_NaN()
		                             : 0.0f;
		std::vector<float> grown(g.cellCount(), fill);
		for (int cy = 0; cy < old.rows; cy++)
			std::copy_n(
			    kv.second.begin() + static_cast<long>(old.index(cy, 0)),
			    old.cols,
			    grown.begin() + static_cast<long>(g.index(cy + dy, dx)));
		kv.second = std::move(grown);
	}
	mrpt::maps::COccupancyGridMap2D grid;
	grid.setSize(
	    static_cast<float>(g.originX), static_cast<float>(g.maxX()),
	    static_cast<float>(g.originY), static_cast<float>(g.maxY()),
	    static_cast<float>(res));
	if (static_cast<int>(grid.getSizeX()) != g.cols ||
	    static_cast<int>(grid.getSizeY()) != g.rows)
		throw Error("occupancy grid geometry mismatch after growing the map");
	if (!empty)
	{
		const auto& raw = m_occupancy.getRawMap();
		for (int cy = 0; cy < old.rows; cy++)
			std::copy_n(
			    raw.begin() + static_cast<long>(old.index(cy, 0)), old.cols,
			    grid.getRow(cy + dy) + dx);
	}
	m_occupancy = std::move(grid);
	m_geometry = g;
	markAllChanged();
}

void SemanticMap::updateCosts()
{
	updateCosts(CellRect::all(m_geometry));
}

void SemanticMap::updateCosts(const CellRect& cells)
{
	CellRect changed;
	updateCostsIn(cells, changed);
	const CellRect c = cells.clipped(m_geometry);
	markChanged(changed);
	if (c.row0 == 0 && c.col0 == 0 && c.row1 == m_geometry.rows &&
	    c.col1 == m_geometry.cols)
		m_costsCurrent = true;
}

void SemanticMap::updateCostsIn(const CellRect& cells, CellRect& changed)
{
	auto& cost = layer(kCost);
	const auto& labels = layer(kLabels);
	const auto& rough = layer(kRoughness);
	const auto& observations = layer(kObservations);
	const CellRect box = cells.clipped(m_geometry);
	const bool walking =
	    m_costModel.options().robotType == TravelCostModel::RobotType::Walking;
	// Walking-only classes (stairs) are solid to the laser; a walking robot
	// climbs them.
	const LabelSet climbable = ClassRegistry::instance().select(
	    [](const ClassInfo& c) { return c.walkingOnly; });
	for (int cy = box.row0; cy < box.row1; cy++)
		for (int cx = box.col0; cx < box.col1; cx++)
		{
			const std::size_t i = m_geometry.index(cy, cx);
			const LabelSet ls(static_cast<LabelSet::mask_t>(labels[i]));
			auto occ = TravelCostModel::Occupancy::Unknown;
			switch (stateOf(observations[i], cx, cy))
			{
				case CellState::Occupied:
					occ = walking && (ls.mask() & climbable.mask()) != 0
					          ? TravelCostModel::Occupancy::Free
					          : TravelCostModel::Occupancy::Occupied;
					break;
				case CellState::Free:
					occ = TravelCostModel::Occupancy::Free;
					break;
				default:
					break;
			}
			const auto c =
			    static_cast<float>(m_costModel.cost(ls, rough[i], occ));
			// NaN-safe: a cost that was NaN counts as changed.
			if (!(cost[i] == c)) changed.add(cy, cx);
			cost[i] = c;
		}
}

std::vector<ObjectInstance> SemanticMap::instances() const
{
	std::vector<ObjectInstance> out;
	for (const auto& o : m_instances)
		if (reported(o)) out.push_back(o);
	return out;
}

std::vector<ObjectInstance> SemanticMap::instances(Label label) const
{
	std::vector<ObjectInstance> out;
	for (const auto& o : instances())
		if (o.label == label) out.push_back(o);
	return out;
}

const ObjectInstance& SemanticMap::instance(int id) const
{
	for (const auto& o : m_instances)
		if (o.id == id) return o;
	throw Error("semantic map has no object with id " + std::to_string(id));
}

const ObjectInstance* SemanticMap::object(int id) const
{
	for (const auto& o : m_instances)
		if (o.id == id) return reported(o) ? &o : nullptr;
	return nullptr;
}

const ObjectInstance* SemanticMap::nearestInstance(
    Label label, const mrpt::math::TPoint2D& p) const
{
	const ObjectInstance* best = nullptr;
	double bestD = std::numeric_limits<double>::infinity();
	for (const auto& o : m_instances)
	{
		if (o.label != label || !reported(o)) continue;
		const double d = std::hypot(o.centroid.x - p.x, o.centroid.y - p.y);
		if (d < bestD)
		{
			bestD = d;
			best = &o;
		}
	}
	return best;
}

int SemanticMap::addInstance(
    Label label, const mrpt::math::TPoint3D& minCorner,
    const mrpt::math::TPoint3D& maxCorner, std::size_t observations)
{
	ObjectInstance o;
	o.id = 1;
	for (const auto& e : m_instances) o.id = std::max(o.id, e.id + 1);
	o.label = label;
	o.minCorner = minCorner;
	o.maxCorner = maxCorner;
	o.centroid = {
	    0.5 * (minCorner.x + maxCorner.x), 0.5 * (minCorner.y + maxCorner.y),
	    0.5 * (minCorner.z + maxCorner.z)};
	o.observations = observations;
	o.views = observations;
	auto& objs = layer(kObjects);
	CellRect painted;
	for (int cy = 0; cy < m_geometry.rows; cy++)
		for (int cx = 0; cx < m_geometry.cols; cx++)
		{
			const double x = m_geometry.centerX(cx), y = m_geometry.centerY(cy);
			if (x >= minCorner.x && x <= maxCorner.x && y >= minCorner.y &&
			    y <= maxCorner.y)
			{
				objs[m_geometry.index(cy, cx)] = static_cast<float>(o.id);
				painted.add(cy, cx);
			}
		}
	m_instances.push_back(o);
	markChanged(painted);
	return o.id;
}

std::vector<std::pair<int, int>> SemanticMap::cellsOf(int id) const
{
	std::vector<std::pair<int, int>> out;
	const auto& objs = get(kObjects);
	for (int cy = 0; cy < m_geometry.rows; cy++)
		for (int cx = 0; cx < m_geometry.cols; cx++)
			if (static_cast<int>(objs[m_geometry.index(cy, cx)]) == id)
				out.emplace_back(cx, cy);
	return out;
}

std::vector<std::pair<int, int>> SemanticMap::goalRegion(
    int id, double reach) const
{
	const ObjectInstance& obj = instance(id);
	auto cells = cellsOf(id);
	if (cells.empty())
	{
		// No cell carries the id (e.g. painted over): use its footprint.
		int x0, y0, x1, y1;
		worldToCell(obj.minCorner.x, obj.minCorner.y, x0, y0);
		worldToCell(obj.maxCorner.x, obj.maxCorner.y, x1, y1);
		for (int cy = std::max(0, y0); cy <= std::min(m_geometry.rows - 1, y1);
		     cy++)
			for (int cx = std::max(0, x0);
			     cx <= std::min(m_geometry.cols - 1, x1); cx++)
				cells.emplace_back(cx, cy);
	}
	const int r = static_cast<int>(std::ceil(reach / m_geometry.resolution));
	const double r2 = std::pow(reach / m_geometry.resolution, 2);
	std::vector<uint8_t> mark(m_geometry.cellCount(), 0);
	std::vector<std::pair<int, int>> out;
	for (const auto& [ox, oy] : cells)
		for (int dy = -r; dy <= r; dy++)
			for (int dx = -r; dx <= r; dx++)
			{
				if (dx * dx + dy * dy > r2) continue;
				const int cx = ox + dx, cy = oy + dy;
				if (!m_geometry.contains(cy, cx)) continue;
				const std::size_t i = m_geometry.index(cy, cx);
				if (mark[i]) continue;
				mark[i] = 1;
				if (cellState(cx, cy) == CellState::Free &&
				    cost(cx, cy) < m_costModel.options().lethalCost)
					out.emplace_back(cx, cy);
			}
	return out;
}

void SemanticMap::restore(
    const GridGeometry& g, std::map<std::string, std::vector<float>> layers,
    const std::vector<int8_t>& logodds, std::vector<ObjectInstance> objs,
    std::size_t sweeps)
{
	for (const auto& kv : layers)
		if (kv.second.size() != g.cellCount())
			throw Error("layer '" + kv.first + "' does not match the map size");
	if (logodds.size() != g.cellCount())
		throw Error("occupancy does not match the map size");
	m_geometry = g;
	for (auto& kv : layers) m_layers[kv.first] = std::move(kv.second);
	for (auto& kv : m_layers)
		if (kv.second.size() != g.cellCount())
			kv.second.assign(g.cellCount(), 0.0f);
	m_occupancy.setSize(
	    static_cast<float>(g.originX), static_cast<float>(g.maxX()),
	    static_cast<float>(g.originY), static_cast<float>(g.maxY()),
	    static_cast<float>(g.resolution));
	for (int cy = 0; cy < g.rows; cy++)
		std::copy_n(
		    logodds.begin() + static_cast<long>(g.index(cy, 0)), g.cols,
		    m_occupancy.getRow(cy));
	m_instances = std::move(objs);
	m_pastSweeps.clear();
	m_sweeps = sweeps;
	markAllChanged();
}

}  // namespace semnav
