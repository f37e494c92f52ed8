/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/maps/COccupancyGridMap2D.h>
#include <mrpt/math/TBoundingBox.h>
#include <mrpt/math/TPoint2D.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/system/COutputLogger.h>
#include <semnav/common/CellRect.h>
#include <semnav/common/ClassRegistry.h>
#include <semnav/common/GridGeometry.h>
#include <semnav/common/LabelSet.h>
#include <semnav/map/ObjectInstance.h>
#include <semnav/map/TravelCostModel.h>

#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <opencv2/core/types.hpp>
#include <string>
#include <vector>

namespace octomap
{
class OcTree;
}

namespace semnav
{
class Sweep;
class LabeledSweep;
struct LabeledRegion;

/** The semantic map: one grid geometry shared by named layers, in the
 * spirit of grid_map's GridMap.
 *
 * - occupancy: an mrpt::maps::COccupancyGridMap2D (log-odds), always the
 *   same geometry as the layers;
 * - float layers by name: "labels" (LabelSet bitmask per cell: the paper's
 *   list of labels of a cell), "cost" (travel cost u, TravelCostModel),
 *   "objects" (instance id, 0 = none), "roughness" (mean R-bar of ground
 *   points), "observations" (times the cell was seen: 0 = unknown), plus
 *   any layer a user adds;
 * - object instances merged across sweeps;
 * - an OctoMap of all points at the map's resolution.
 *
 * Sweeps are inserted at a robot pose; the grid grows to hold what is seen.
 * World frame: x, y on the floor, z up. */
class SemanticMap : public mrpt::system::COutputLogger
{
public:
	struct TOptions : public mrpt::config::CLoadableOptions
	{
		void loadFromConfigFile(
		    const mrpt::config::CConfigFileBase& c,
		    const std::string& section) override;
		void saveToConfigFile(
		    mrpt::config::CConfigFileBase& c,
		    const std::string& section) const override;

		double resolution = 0.05;
		/** Extra room added around new points when the grid grows (m). */
		double growMargin = 2.0;
		/** Points from floor + obstacleMinHeight to robotHeight are
		 * obstacles (m). */
		double obstacleMinHeight = 0.02;
		double robotHeight = 1.0;
		/** The robot's footprint radius: the cells it stands on are free
		 * (the laser cannot see them) (m). */
		double robotRadius = 0.3;
		/** Occupancy update per sweep for a hit / a free cell. */
		double hitProbability = 0.8;
		double freeProbability = 0.35;
		/** cellState() thresholds on the occupancy probability. */
		double occupiedThreshold = 0.65;
		double freeThreshold = 0.35;
		/** Door and stairs detections of one label closer than this, or
		 * whose footprints overlap (a staircase seen from several sides),
		 * are one object (m). */
		double mergeDistance = 0.6;
		/** Washbasin and wastebasket detections join an instance only
		 * within this distance of one of its sightings, footprints aside:
		 * a first detection whose box held two washbasins side by side
		 * must not make them one (m). */
		double objectMergeDistance = 0.4;
		/** Cascade objects (washbasin, wastebasket, stairs) seen in fewer
		 * sweeps are not reported (one-off detections). */
		int minObservations = 1;
		/** The same for doors (found by the rules, not a cascade). */
		int doorMinObservations = 1;
		/** Doors detected in fewer than this fraction of the sweeps that
		 * had their place in view (door views: SweepView::visibleShare()
		 * at least doorViewMinVisibleShare, within doorViewMaxBearingDeg,
		 * >= doorViewMinPixels) are not reported: a wall or furniture piece
		 * the door rules took for a door in one of several looks. 0: no
		 * check. */
		double doorMinDetectionRatio = 0.35;
		/** A door is sure when one sighting showed a whole leaf: at least
		 * this wide... */
		double doorSureMinWidth = 0.7;
		/** ...and this high (m)... */
		double doorSureMinHeight = 1.8;
		/** ...seen at most this far from straight on (deg). Its shape score
		 * (ObjectInstance::bestShapeScore) is the share of such a leaf
		 * its best sighting within this angle showed. */
		double doorSureMaxIncidenceDeg = 45;
		/** Sure doors need only this detection ratio: a door seen whole
		 * and square once, missed in looks from afar or at a slant. */
		double doorSureMinDetectionRatio = 0.2;
		/** A sweep has a door in view when at least this share of the
		 * points over its face is in the field of view and unhidden. */
		double doorViewMinVisibleShare = 0.6;
		/** Door views count only within this bearing of the robot's
		 * heading (deg)... */
		double doorViewMaxBearingDeg = 80;
		/** ...seen at most this far from straight on (deg; the angle
		 * between the line of sight and the door's normal, from its
		 * regions' normals): the rules rarely find a door seen at a
		 * grazing angle along a corridor... */
		double doorViewMaxIncidenceDeg = 60;
		/** ...and where the door would cover this many pixels (from its
		 * typical size, foreshortened, and distance): the door rules rarely
		 * find a door far away, where it is small. */
		int doorViewMinPixels = 150;
		/** Sweeps kept to count the views of a door first detected later
		 * (the views before its first detection); 0: views from the first
		 * detection on only. */
		int doorViewHistory = 30;
		/** Cascade objects detected in fewer than this fraction of the
		 * sweeps that had them in view are not reported (furniture that a
		 * cascade took for an object once in many looks). */
		double minDetectionRatio = 0.6;
		/** The same for stairs, whose cascade finds a flight in about half
		 * of the sweeps that see it (a table taken for stairs: one in
		 * three or fewer). */
		double stairsMinDetectionRatio = 0.4;
		/** A cascade object is sure when one of its detections scored at
		 * least this on its class's shape check
		 * (ObjectInstance::bestShapeScore). */
		double sureShapeScore = 0.95;
		/** Sure objects need only this detection ratio (if lower than
		 * their class's): a real object the cascade missed in a few
		 * looks. */
		double sureMinDetectionRatio = 0.5;
		/** Objects that are not sure need this many detections: a single
		 * doubtful detection is no object. */
		int unsureMinObservations = 2;
		/** Objects that are not sure but scored at least this on their shape
		 * check need only minObservations detections, not
		 * unsureMinObservations ([0, 1]; 0: none): of the wastebaskets
		 * and washbasins detected once (tuning seeds 0-96), 11 of the 24
		 * true ones scored 0.81-0.94, the false ones 0.40-0.75. */
		double unsureOnceMinShapeScore = 0.8;
		/** Stairs that are not sure whose typical detection (the median
		 * width of their sightings) is narrower than this are not
		 * reported: a low box (with a wastebasket beside it) taken for a
		 * flight is 0.5-0.7 m wide, a flight's detections 0.74 m and more (m;
		 * 0: no check; a map loaded without sighting sizes keeps them). */
		double unsureStairsMinWidth = 0.8;
		/** Wastebaskets that are not sure none of whose sightings is at
		 * most this wide are not reported: the detections of a real
		 * wastebasket are 0.16-0.26 m wide at least once, a plant pot's
		 * (its foliage) taken for one 0.33 m and more every time (m; 0: no
		 * check; a map loaded without sighting sizes keeps them). */
		double unsureWastebasketMaxWidth = 0.3;
		/** ...unless they scored at least this on their shape check ([0,
		 * 1]; 0: no exception): on tuning buildings 0-159 the false
		 * wastebaskets the doubtful-object rules hold back scored at most
		 * 0.77, while real ones seen only wide (0.36-0.44 m, a bin seen
		 * from its corner) scored 0.90-0.94 (docs/mapping.md). */
		double unsureWastebasketWideMinShapeScore = 0.8;
		/** Cascade objects that are not sure whose centroid lies within
		 * this distance of a sure reported cascade object of another
		 * label are not reported: one object is not two (a wastebasket
		 * taken for a washbasin too) (m; 0: no check). */
		double unsureOtherLabelDistance = 0.3;
		/** A sweep has an object in view when it has line of sight to its
		 * centroid and the object would cover at least this many pixels
		 * of it (from its extent and distance). */
		int viewMinPixels = 150;
		/** Views count only within this bearing of the robot's heading
		 * (deg): beside the robot the sweep's poles smear objects and the
		 * cascades rarely fire. */
		double viewMaxBearingDeg = 90;
		/** Washbasins whose detections never reach this height are not
		 * reported (side tables, chairs, steps taken for one) (m). */
		double washbasinMinTop =
		    classInfo(Label::Washbasin).plausibility.minInstanceTop;
		/** Washbasins with no wall cell within this distance of their
		 * centroid are not reported (free-standing tables taken for
		 * one); 0 = no check (m). */
		double washbasinMaxWallDistance =
		    classInfo(Label::Washbasin).plausibility.maxWallDistance;
		/** Stairs whose detections never come down to this height are not
		 * reported: a flight starts at the floor, a table top taken for
		 * one does not (m). */
		double stairsMaxBottom =
		    classInfo(Label::Stairs).plausibility.maxBottom;
		/** Sure stairs (TOptions::sureShapeScore) need only come down to
		 * this height (m; 0: stairsMaxBottom for them too): a flight
		 * whose lowest riser was cut from every detection box is still a
		 * flight when its shape says so. */
		double sureStairsMaxBottom = 0.2;
		/** A staircase's centroid (x, y) is the centre of the cells
		 * labelled stairs (and not wall, washbasin or wastebasket in any
		 * sweep) connected to its sightings within its footprint: one
		 * detection box often holds part of the flight only, the labelled
		 * cells of all sweeps hold all of it. */
		bool stairsCentroidFromCells = true;
		/** Of those cells, only the ones labelled stairs in at least this
		 * share of the sweeps that labelled its most labelled cell (layer
		 * "stairs_sweeps"): one false detection on a table beside a
		 * flight labels the table once, the flight's cells many times.
		 * [0, 1]; 0: every labelled cell. */
		double stairsMinCellShare = 0.1;
		/** The cells connected to a flight's sightings are looked for up
		 * to this far outside its footprint (m; 0: inside it): the
		 * detection boxes often hold the part of the flight seen best
		 * (its near side, its lower steps), its risers run on. */
		double stairsCellMargin = 0;
		/** Cells of the flight this close to one another are connected
		 * (m; at most one cell: 8-connected): from below, the treads of
		 * the upper steps are hidden and only their risers are labelled,
		 * lines a run apart. */
		double stairsCellGap = 0;
		/** Cells of a flight this far apart across its risers are connected
		 * (m; 0: off): seen from its foot, a flight's upper treads are
		 * hidden and its risers are rows of cells a run apart. The axis
		 * across the risers is the one along which the footprint's cells
		 * pile up most. */
		double stairsRiserGap = 0.4;
		/** The riser gap joins only a row of cells at least this long
		 * along the risers (m; one-cell gaps allowed): a chair's legs or a
		 * stray cell in front of the flight are no riser. */
		double stairsRiserMinRow = 0.5;
		/** A sweep gives a door one sighting (its centroid, see
		 * ObjectInstance::addSighting()): true: of the sweep's door regions
		 * merged into it, the one with the most pixels; false: the first
		 * merged (row-major order), often a 0.1-0.3 m piece at the sensor's
		 * height that the door rule labelled door beside the door, which
		 * then set the door's place. */
		bool doorSightingLargestRegion = true;
		/** A door region at least this wide gives as its sighting the
		 * middle of its bounding box (horizontally; height: its points'
		 * mean) rather than the mean of its points (m; 0: never). A wide
		 * door seen obliquely has many more points on its near side, which
		 * pulled the mean 0.3-0.5 m toward the sensor's side of a double
		 * door; narrower regions keep the mean, which a few stray points at
		 * an edge move less than they move the box. With the two guards
		 * below (docs/generated-scenes-log.md, parts 6 and 8). */
		double doorSightingBoxCentreMinWidth = 1.5;
		/** ...and at most this wide (m; 0: no limit): a wider region
		 * swallowed wall beside the door, and its box's middle is farther
		 * off than its points' mean (indoor_54: a 2.99 m region, 0.93 m
		 * off, which then made a second door). */
		double doorSightingBoxCentreMaxWidth = 2.2;
		/** Such a region is sighted at the middle of its columns along the
		 * wall whose points span at least this share of its height, not
		 * the middle of its box (0: the box): a leaf fills its opening from
		 * bottom to top, a strip of wall the region took in beside it does
		 * not (docs/mapping.md). */
		double doorSightingFullHeightShare = 0.75;
		/** Door regions higher than this make no door instance and join
		 * none (m; 0: no limit): a stretch of wall from floor to ceiling
		 * that the rules took for a door, seen at a grazing angle. */
		double doorRegionMaxHeight = 2.5;
		/** A door region's footprint (the box its instance grows by, which
		 * merges it with an instance it overlaps) is the world box of its
		 * points; false: the world box around its robot-frame box, which
		 * for a wall seen at 45 deg to the robot's axes is as deep as it is
		 * wide and bridged neighbouring doors (one instance held two doors
		 * and was reported at one of them). Regions without points (a map's
		 * tests' hand-made regions) keep the box around their box. */
		bool doorFootprintFromPoints = true;
		/** Doors whose merged extent is lower than this are not reported
		 * (fragments of walls or furniture taken for a door, 0.1-0.5 m on
		 * the tuning buildings; a door seen close shows 0.64-1.07 m below
		 * the top of the tilt range) (m). */
		double doorMinHeight = classInfo(Label::Door).plausibility.minHeight;
		/** Doors none of whose sightings (one region per sweep) is at
		 * least this wide are not reported: a strip of wall, jamb or leaf
		 * edge the rules took for a door, or a door seen so cut that its
		 * place is off by half its width (m; 0: no check; a map loaded
		 * without sighting sizes keeps its doors). */
		double doorMinWidth = 0.3;
		/** Two door instances side by side in one wall are the two leaves
		 * of a double door, joined into one door at their middle
		 * (joinDoubleDoors()), when together at most this wide along the
		 * wall (their footprints) (m; 0: no join; the generated double
		 * doors are <= 2.0 m; with the leaf width ratio and leaf offset
		 * checks, on tuning buildings 0-99 it removed 3 of 6 spurious doors
		 * and lost none found on 100-159, docs/mapping.md)... */
		double doubleDoorMaxWidth = 2.2;
		/** ...each at most this wide (its typical detection) (m)... */
		double doubleDoorMaxLeafWidth = 1.15;
		/** ...their centroids at most this far from one plane, their
		 * normals within 15 deg (m)... */
		double doubleDoorMaxPlaneOffset = 0.1;
		/** ...and with no stretch of wall longer than this between their
		 * centroids (cells labelled wall and never door): the wall between
		 * the doors of two neighbouring rooms (m). */
		double doubleDoorMaxWall = 0.3;
		/** ...the narrower leaf at least this share of the wider (their
		 * typical detections; the leaves of a double door are alike, a
		 * strip of wall or jamb beside a single door is not; 0: no
		 * check)... */
		double doubleDoorMinLeafWidthRatio = 0.7;
		/** ...and their centroids at most this far from one plane (the
		 * two leaves hang in one plane; a strip of wall beside a door
		 * recessed into its gap lies at the wall's face, the door's inset
		 * away) (m; 0: doubleDoorMaxPlaneOffset only). */
		double doubleDoorMaxLeafOffset = 0.05;
		/** Two reported door instances in one wall (normals within 15 deg,
		 * centroids at most doubleDoorMaxPlaneOffset from one plane) whose
		 * footprints overlap and whose centroids are at most this far apart
		 * are one door found twice (the two leaves of a double door seen
		 * apart, or a grazing look at a door placed beside it): joined at
		 * the mean of their centroids weighted by their detections (m; 0:
		 * no join). Two doors of neighbouring rooms are >= 1.5 m apart in
		 * the generated buildings. */
		double doorJoinDistance = 0.8;
		/** A door seen in no more sweeps than another in its wall, whose
		 * footprint lies at least this share inside the other's along the
		 * wall and within doubleDoorMaxWidth of it, is a piece of that
		 * door and joins it at the other's centroid (0: no join): a strip
		 * at a double door's edge, farther than doorJoinDistance from the
		 * door's middle once wide regions are sighted at theirs. */
		double doorJoinContainedShare = 0.8;
		/** A door's centroid weighs each of its sightings (those within
		 * half the merge distance of their median) by the square of its
		 * region's width, widths above this counting as this: a cut view
		 * (edge of the field of view, half hidden, grazing) or a piece of
		 * leaf or jamb is narrower than a whole view and pulls it less; a
		 * region that swallowed wall beside the door weighs no more than
		 * one about a door wide (ObjectInstance::recentre(); m; 0: the
		 * plain mean). */
		double doorCentroidMaxWeightWidth = 1.5;
		/** Insert points into the OctoMap. */
		bool octomap = true;
		TravelCostModel::TOptions cost;
	};

	enum class CellState
	{
		Unknown,
		Free,
		Occupied
	};

	SemanticMap();
	explicit SemanticMap(const TOptions& options);
	~SemanticMap() override;
	SemanticMap(const SemanticMap&) = delete;
	SemanticMap& operator=(const SemanticMap&) = delete;

	// ---- geometry -------------------------------------------------------
	const GridGeometry& geometry() const { return m_geometry; }
	/** Cell of a world point; false outside the map. */
	bool worldToCell(double x, double y, int& cx, int& cy) const
	{
		return m_geometry.worldToCell(x, y, cx, cy);
	}
	/** Centre of a cell; false outside the map. */
	bool cellToWorld(int cx, int cy, double& x, double& y) const
	{
		return m_geometry.cellToWorld(cx, cy, x, y);
	}
	/** Grows the grid (all layers) to hold the box; contents kept. */
	void growToInclude(double xmin, double ymin, double xmax, double ymax);

	// ---- layers ---------------------------------------------------------
	bool exists(const std::string& layer) const;
	/** Adds a layer filled with `value` (no-op if it exists). */
	void add(const std::string& layer, float value = 0.0f);
	/** Throws Error if the layer does not exist. */
	const std::vector<float>& get(const std::string& layer) const;
	/** Write access: counts as a change of the whole map (see
	 * changesSince()). */
	std::vector<float>& get(const std::string& layer);
	float at(const std::string& layer, int cx, int cy) const
	{
		return get(layer)[m_geometry.index(cy, cx)];
	}
	/** Write access: counts as a change of the whole map. */
	float& at(const std::string& layer, int cx, int cy)
	{
		return get(layer)[m_geometry.index(cy, cx)];
	}
	std::vector<std::string> layers() const;

	LabelSet labels(int cx, int cy) const;
	double cost(int cx, int cy) const { return at("cost", cx, cy); }
	int objectId(int cx, int cy) const
	{
		return static_cast<int>(at("objects", cx, cy));
	}
	/** Occupancy probability (0.5 for a cell never seen). */
	double occupancy(int cx, int cy) const;
	CellState cellState(int cx, int cy) const;
	/** cellState() of the cells of `cells` (clipped to the grid), row by
	 * row. */
	std::vector<CellState> cellStates(const CellRect& cells) const;

	const mrpt::maps::COccupancyGridMap2D& occupancyGrid() const
	{
		return m_occupancy;
	}
	/** Write access: counts as a change of the whole map. */
	mrpt::maps::COccupancyGridMap2D& occupancyGrid()
	{
		markAllChanged();
		return m_occupancy;
	}

	// ---- change tracking ------------------------------------------------
	/** What may have changed between two versions: the cells whose state
	 * (cellState()), labels, cost or object id changed (their bounding
	 * box), or the whole map. Other layers (observation counts, roughness,
	 * log-odds within a state) are not tracked; object instances
	 * (reported or not, footprints) may change with any version. */
	struct Changes
	{
		/** Anything (the grid grew, was restored or written through a
		 * non-const accessor, or the version is too old to know). */
		bool all = false;
		/** Rows and columns of the current grid; meaningless when all. */
		CellRect cells;
		/** The cells any layer of which was written, observation counts,
		 * occupancy and roughness included (holds `cells`). */
		CellRect touched;
		bool none() const { return !all && cells.empty(); }
	};
	/** Increases with every change of the contents: insert(),
	 * addInstance(), updateCosts(), restore(), growth, and every call of a
	 * non-const accessor (get(), at(), occupancyGrid()). */
	std::uint64_t version() const { return m_version; }
	/** Changes since `version` (a value of version()); cheap: the last
	 * kChangeHistory changes are kept, older versions give all. */
	Changes changesSince(std::uint64_t version) const;
	/** Records a change of these cells (e.g. writes through a reference a
	 * non-const accessor returned before the last version() was taken). */
	void markChanged(const CellRect& cells);
	/** The same, with the other cells written (see Changes::touched). */
	void markChanged(const CellRect& cells, const CellRect& touched);
	/** Records a change of the whole map. */
	void markAllChanged();
	static constexpr std::size_t kChangeHistory = 64;

	// ---- insertion ------------------------------------------------------
	/** Inserts a classified sweep taken at `robotPose` (world frame). */
	void insert(
	    const Sweep& sweep, const LabeledSweep& labeled,
	    const mrpt::poses::CPose2D& robotPose);
	/** Recomputes the cost layer of every cell from its labels, roughness
	 * and occupancy. */
	void updateCosts();
	/** The same inside `cells`, recording the cells whose cost changed
	 * (after writing labels or occupancy there: record those with
	 * markChanged()). */
	void updateCosts(const CellRect& cells);
	std::size_t sweepsInserted() const { return m_sweeps; }

	// ---- objects --------------------------------------------------------
	/** All instances, including those below minObservations. */
	const std::vector<ObjectInstance>& allInstances() const
	{
		return m_instances;
	}
	/** True when an instance passes the reporting rules (observations,
	 * plausible size). */
	bool reported(const ObjectInstance& o) const;
	/** The first reporting rule an instance fails, named by its TOptions
	 * key (e.g. "door_min_detection_ratio"); empty when it is reported. */
	std::string unreportedReason(const ObjectInstance& o) const;
	/** Instances that pass the reporting rules. */
	std::vector<ObjectInstance> instances() const;
	std::vector<ObjectInstance> instances(Label label) const;
	/** Throws Error for an unknown id (candidates included). */
	const ObjectInstance& instance(int id) const;
	/** The object (a reported instance) with this id, or nullptr: goals
	 * by id go through here (docs/mapping.md, "One rule for which objects
	 * exist"). */
	const ObjectInstance* object(int id) const;
	/** Nearest reported instance of `label` to a point (Euclidean), or
	 * nullptr. */
	const ObjectInstance* nearestInstance(
	    Label label, const mrpt::math::TPoint2D& p) const;
	/** Adds an instance directly (ground truth, tests, an operator's
	 * annotation) with the next free id; the cells whose centre lies in its
	 * footprint [minCorner, maxCorner] (x, y) get the id in the "objects"
	 * layer. The centroid is the box centre. Returns the id. */
	int addInstance(
	    Label label, const mrpt::math::TPoint3D& minCorner,
	    const mrpt::math::TPoint3D& maxCorner, std::size_t observations = 1);
	/** Cells whose "objects" layer holds the instance. */
	std::vector<std::pair<int, int>> cellsOf(int id) const;
	/** Goal region of an instance: free cells within `reach` metres of its
	 * cells (for a door: the free cells in front of and behind it). */
	std::vector<std::pair<int, int>> goalRegion(int id, double reach) const;

	// ---- 3D -------------------------------------------------------------
	const octomap::OcTree& octree() const { return *m_octree; }
	/** Write access: the next insert() recomputes all inner nodes. */
	octomap::OcTree& octree()
	{
		m_octreeInnerCurrent = false;
		return *m_octree;
	}

	const TOptions& options() const { return m_options; }
	const TravelCostModel& costModel() const { return m_costModel; }

	/** Replaces the contents (used by the loader). */
	void restore(
	    const GridGeometry& g, std::map<std::string, std::vector<float>> layers,
	    const std::vector<int8_t>& logodds, std::vector<ObjectInstance> objs,
	    std::size_t sweeps);

private:
	struct WorldPoint;
	/** The world box of each region's points (indexed by region id; a
	 * region without points: TBoundingBox::PlusMinusInfinity()). */
	static std::vector<mrpt::math::TBoundingBox> regionPointBoxes(
	    const LabeledSweep& labeled, const std::vector<WorldPoint>& pts);
	struct SweepEvidence;
	/** Layer by name, writable, not counted as a change (internal). */
	std::vector<float>& layer(const char* name);
	/** updateCosts() inside `cells` (clipped); adds the cells whose cost
	 * changed to `changed` (the caller records the change). */
	void updateCostsIn(const CellRect& cells, CellRect& changed);
	/** cellState() from a cell's observation count. */
	CellState stateOf(float observations, int cx, int cy) const;
	/** Where the sweep's sensor stood (its middle row), world frame. */
	static mrpt::math::TPoint2D sensorPosition(
	    const Sweep& sweep, const mrpt::poses::CPose3D& robot,
	    const mrpt::poses::CPose2D& robotPose);
	/** The cells a sweep can change: its points', the rays' from the
	 * sensor to them, the robot's footprint (clipped to the grid). */
	CellRect sweepWindow(
	    const std::vector<WorldPoint>& pts, const mrpt::math::TPoint2D& sensor,
	    const mrpt::poses::CPose2D& robotPose) const;
	/** World points of the sweep's valid pixels; grows the grid to hold
	 * them and the robot. */
	std::vector<WorldPoint> worldPoints(
	    const LabeledSweep& labeled, const mrpt::poses::CPose3D& robot,
	    const mrpt::poses::CPose2D& robotPose);
	/** Labels (layer), hits, free ends and roughness of the points. */
	void accumulatePoints(
	    const std::vector<WorldPoint>& pts, const LabeledSweep& labeled,
	    SweepEvidence& e);
	/** Cells seen free: on the rays to free ends, under the robot. */
	void markSeenFree(
	    const Sweep& sweep, const mrpt::poses::CPose3D& robot,
	    const mrpt::poses::CPose2D& robotPose, SweepEvidence& e) const;
	/** The points into the OctoMap (leaves, then the inner nodes above
	 * them). */
	void insertIntoOctree(const std::vector<WorldPoint>& pts);
	/** Occupancy, observation counts and roughness from the evidence. */
	void updateCells(SweepEvidence& e);
	/** Sets the "objects" layer to `id` in the cells of the pixels in `box`
	 * for which belongs(row, col). */
	void paintObject(
	    SweepEvidence& e, int id, const cv::Rect& box,
	    const std::function<bool(int, int)>& belongs);
	/** Merges the sweep's detections into instances. */
	void insertDetections(
	    const LabeledSweep& labeled, const mrpt::poses::CPose3D& robot,
	    SweepEvidence& e, std::vector<int>& seenThisSweep,
	    std::vector<int>& viewedThisSweep);
	/** Merges the labelled regions of region classes (doors) into
	 * instances. */
	void insertRegions(
	    const LabeledSweep& labeled, const mrpt::poses::CPose3D& robot,
	    const std::vector<WorldPoint>& pts, SweepEvidence& e,
	    std::vector<int>& seenThisSweep);
	/** Reporting rules of a class: its registry row, with the built-ins'
	 * configured values. */
	ClassInfo::Plausibility plausibility(Label l) const;
	/** Counts a view of every instance the sweep had in line of sight. */
	void countViews(
	    const Sweep& sweep, const mrpt::poses::CPose3D& robot,
	    std::vector<int>& viewedThisSweep);
	/** Whether the sweep, taken at `robot`, had the door `o` in view
	 * (TOptions::doorMinDetectionRatio). */
	bool doorInView(
	    const Sweep& sweep, const mrpt::poses::CPose3D& robot,
	    const ObjectInstance& o) const;
	/** Door views: a view of the instances merged from this sweep's
	 * regions that countViews() did not count (detected, so in view), and
	 * for the doors first detected in it, their views in the sweeps kept
	 * (m_pastSweeps). */
	void countDoorViews(
	    std::size_t firstNew, const std::vector<int>& seenThisSweep,
	    std::vector<int>& viewedThisSweep);
	/** Adds a region's normal (robot frame) to a door's normalSum. */
	static void addNormal(
	    const mrpt::poses::CPose3D& robot, const mrpt::math::TPoint3D& normal,
	    ObjectInstance& o);
	/** The instance with this id, or nullptr. */
	ObjectInstance* instanceWithId(int id);
	/** A detected instance was in view: one view per sweep (a new instance,
	 * or a centroid the view test missed). */
	static void countDetectedView(
	    ObjectInstance& o, std::vector<int>& viewedThisSweep);
	/** Joins pairs of door instances side by side in one wall, each about
	 * a leaf wide, into one door (ObjectInstance::leaves = 2) at their
	 * middle (TOptions::doubleDoorMaxWidth), and pairs that are one door
	 * found twice (TOptions::doorJoinDistance) or a door and a piece of it
	 * (TOptions::doorJoinContainedShare); the joined instance keeps
	 * the lower id, the "objects" cells of the other get it. */
	void joinDoubleDoors(CellRect& changed);
	/** Whether door instances `a` and `b` are the two leaves of one
	 * double door (see joinDoubleDoors()). */
	bool leavesOfOneDoor(
	    const ObjectInstance& a, const ObjectInstance& b) const;
	/** Longest stretch (m) of cells labelled wall and never door on the
	 * segment between two points. */
	double longestWallBetween(
	    const mrpt::math::TPoint3D& a, const mrpt::math::TPoint3D& b) const;
	/** Whether door instances `a` and `b` are one door found twice: both
	 * reported, centroids within TOptions::doorJoinDistance, in one wall,
	 * footprints overlapping (see joinDoubleDoors()). */
	bool duplicatesOfOneDoor(
	    const ObjectInstance& a, const ObjectInstance& b) const;
	/** Whether door instance `part` is a piece of door `whole`: both
	 * reported, in one wall, `part` seen in no more sweeps and its
	 * footprint along the wall at least TOptions::doorJoinContainedShare
	 * inside that of `whole` (see joinDoubleDoors()). */
	bool pieceOfDoor(
	    const ObjectInstance& whole, const ObjectInstance& part) const;
	/** `a` takes in m_instances[bIndex] (sightings, footprint, normals,
	 * the larger counts; the "objects" cells of b get a's id), which is
	 * erased. */
	void absorbDoor(ObjectInstance& a, int bIndex, CellRect& changed);
	/** A double door's centroid from its sightings: the middle between
	 * the mean of those on either side of `middle` along its wall
	 * (unchanged when one side has none). */
	static void centreOnLeaves(
	    ObjectInstance& o, const mrpt::math::TPoint3D& middle);
	/** Keeps the sweep for countDoorViews() (TOptions::doorViewHistory). */
	void keepSweep(const Sweep& sweep, const mrpt::poses::CPose3D& robot);
	/** Sets a staircase's centroid (x, y) from its labelled cells (see
	 * TOptions::stairsCentroidFromCells). */
	void centreOnCells(ObjectInstance& o) const;
	/** Layer names: the labels (a LabelSet mask per cell), travel cost,
	 * object ids, roughness and observation counts... */
	static const char* const kLabels;
	static const char* const kCost;
	static const char* const kObjects;
	static const char* const kRoughness;
	static const char* const kObservations;
	/** ...and per cell, the sweeps that labelled a point in it stairs. */
	static const char* const kStairsSweeps;
	/** True when a cell labelled wall lies within `radius` of (x, y). */
	bool wallWithin(double x, double y, double radius) const;
	/** The reporting rules for cascade objects that are not sure
	 * (TOptions::unsureStairsMinWidth, unsureWastebasketMaxWidth,
	 * unsureOtherLabelDistance): the key of the first that `o` fails, or
	 * empty. */
	std::string doubtfulObjectReason(const ObjectInstance& o) const;
	/** True for a detected object (not a region such as a door) whose shape
	 * check was sure (TOptions::sureShapeScore). */
	bool sureDetection(const ObjectInstance& o) const;
	/** A door region's shape score: the share of a whole leaf
	 * (TOptions::doorSureMinWidth x doorSureMinHeight) it shows when seen
	 * within doorSureMaxIncidenceDeg of straight on, else 0. */
	double doorLeafScore(const LabeledRegion& reg) const;
	/** The width cap of a label's sighting weights
	 * (TOptions::doorCentroidMaxWeightWidth for doors, 0: unweighted). */
	double sightingMaxWeightWidth(Label label) const;
	void mergeObject(
	    Label label, const mrpt::math::TPoint3D& centroid,
	    const mrpt::math::TPoint3D& size, const mrpt::math::TBoundingBox& box,
	    double shapeScore, std::vector<int>& seenThisSweep, int& id);

	TOptions m_options;
	TravelCostModel m_costModel;
	GridGeometry m_geometry;
	std::map<std::string, std::vector<float>> m_layers;
	mrpt::maps::COccupancyGridMap2D m_occupancy;
	std::vector<ObjectInstance> m_instances;
	struct PastSweep;
	/** The last TOptions::doorViewHistory sweeps, oldest first (shared:
	 * PastSweep is complete in SemanticMapDoorViews.cpp only). */
	std::deque<std::shared_ptr<const PastSweep>> m_pastSweeps;
	std::unique_ptr<octomap::OcTree> m_octree;
	/** False after write access to the OctoMap from outside: its inner
	 * nodes may not match their children. */
	bool m_octreeInnerCurrent = true;
	std::size_t m_sweeps = 0;
	struct Change
	{
		std::uint64_t version;
		bool all;
		CellRect cells, touched;
	};
	std::uint64_t m_version = 0;
	/** Changes after m_historyStart, oldest first. */
	std::deque<Change> m_changes;
	std::uint64_t m_historyStart = 0;
	/** False when layers may have been written or loaded since the cost
	 * layer was last recomputed everywhere: the next insert() recomputes
	 * it everywhere (otherwise only where the sweep touched). */
	bool m_costsCurrent = true;
};

}  // namespace semnav
