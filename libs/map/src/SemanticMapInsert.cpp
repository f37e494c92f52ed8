/* semnav: semantic navigation from tilting-laser sweeps */
// SemanticMap::insert(): projects a classified sweep into the grid layers,
// the occupancy grid, the object instances and the OctoMap.
#include <mrpt/poses/CPose3D.h>
#include <octomap/OcTree.h>
#include <semnav/common/ClassRegistry.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/perception/LabeledSweep.h>
#include <semnav/scan/Sweep.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>

#include "DoorSighting.h"

namespace semnav
{
namespace
{
/** Calls f(cx, cy) for the cells of the segment (x0,y0)-(x1,y1) (Bresenham,
 * both ends included). */
template <typename F>
void traceLine(int x0, int y0, int x1, int y1, F&& f)
{
	const int dx = std::abs(x1 - x0), sx = x0 < x1 ? 1 : -1;
	const int dy = -std::abs(y1 - y0), sy = y0 < y1 ? 1 : -1;
	int err = dx + dy;
	for (;;)
	{
		f(x0, y0);
		if (x0 == x1 && y0 == y1) break;
		const int e2 = 2 * err;
		if (e2 >= dy)
		{
			err += dy;
			x0 += sx;
		}
		if (e2 <= dx)
		{
			err += dx;
			y0 += sy;
		}
	}
}

/** The inner nodes on the paths from the root to `keys` (the leaves a
 * lazy updateNode() changed), children first: what
 * OcTree::updateInnerOccupancy() recomputes everywhere, done where it can
 * change. `codes`: the keys' Morton codes (child index at depth d in bits
 * 3 (15 - d) .. 3 (15 - d) + 2), sorted and unique. */
void updateInnerOccupancyAlong(
    octomap::OcTree& tree, octomap::OcTreeNode* node, unsigned depth,
    const std::uint64_t* begin, const std::uint64_t* end)
{
	if (!tree.nodeHasChildren(node)) return;
	if (depth < tree.getTreeDepth())
	{
		const unsigned shift = 3 * (tree.getTreeDepth() - 1 - depth);
		for (const std::uint64_t* b = begin; b != end;)
		{
			const unsigned child = (*b >> shift) & 7;
			const std::uint64_t* e = b;
			while (e != end && ((*e >> shift) & 7) == child) ++e;
			if (tree.nodeChildExists(node, child))
				updateInnerOccupancyAlong(
				    tree, tree.getNodeChild(node, child), depth + 1, b, e);
			b = e;
		}
	}
	node->updateOccupancyChildren();
}

/** Bit b of v moved to bit 3 b (16 bits). */
std::uint64_t spreadBits(std::uint64_t v)
{
	v &= 0xffff;
	v = (v | v << 16) & 0x0000ff0000ffull;
	v = (v | v << 8) & 0x00f00f00f00full;
	v = (v | v << 4) & 0x0c30c30c30c3ull;
	v = (v | v << 2) & 0x249249249249ull;
	return v;
}

/** Morton code of a key (see updateInnerOccupancyAlong; OcTree keys have
 * 16 bits, the tree depth). */
std::uint64_t mortonCode(const octomap::OcTreeKey& k)
{
	return spreadBits(k.k[0]) | spreadBits(k.k[1]) << 1 |
	       spreadBits(k.k[2]) << 2;
}

/** Bit 3 b of v moved to bit b (spreadBits() undone). */
std::uint16_t compactBits(std::uint64_t v)
{
	v &= 0x249249249249ull;
	v = (v | v >> 2) & 0x0c30c30c30c3ull;
	v = (v | v >> 4) & 0x00f00f00f00full;
	v = (v | v >> 8) & 0x0000ff0000ffull;
	v = (v | v >> 16) & 0xffffull;
	return static_cast<std::uint16_t>(v);
}

octomap::OcTreeKey keyOfCode(std::uint64_t m)
{
	return octomap::OcTreeKey(
	    compactBits(m), compactBits(m >> 1), compactBits(m >> 2));
}

/** World-frame bounding box of the robot-frame box [a, b]. */
mrpt::math::TBoundingBox toWorldBox(
    const mrpt::poses::CPose3D& robot, const mrpt::math::TPoint3D& a,
    const mrpt::math::TPoint3D& b)
{
	auto box = mrpt::math::TBoundingBox::PlusMinusInfinity();
	for (int k = 0; k < 8; k++)
		box.updateWithPoint(robot.composePoint(
		    {(k & 1) ? b.x : a.x, (k & 2) ? b.y : a.y, (k & 4) ? b.z : a.z}));
	return box;
}
}  // namespace

struct SemanticMap::WorldPoint
{
	float x, y, z;
	float height;  // above the floor
	int r, c;
};

std::vector<mrpt::math::TBoundingBox> SemanticMap::regionPointBoxes(
    const LabeledSweep& ls, const std::vector<WorldPoint>& pts)
{
	std::vector<mrpt::math::TBoundingBox> boxes(
	    ls.regions.size(), mrpt::math::TBoundingBox::PlusMinusInfinity());
	if (ls.regionIds.empty()) return boxes;
	for (const auto& p : pts)
	{
		const int id = ls.regionIds.at<int32_t>(p.r, p.c);
		if (id < 0 || static_cast<std::size_t>(id) >= boxes.size()) continue;
		boxes[static_cast<std::size_t>(id)].updateWithPoint({p.x, p.y, p.z});
	}
	return boxes;
}

/** What one sweep says of each cell of its window (the cells it can
 * reach), and where its pixels fell. */
struct SemanticMap::SweepEvidence
{
	SweepEvidence(const CellRect& window_, int rows_, int cols_)
	    : window(window_),
	      width(window_.col1 - window_.col0),
	      hit(area(), 0),
	      freeEnd(area(), 0),
	      seenFree(area(), 0),
	      roughSum(area(), 0.0f),
	      roughN(area(), 0),
	      rows(rows_),
	      cols(cols_),
	      cellOfPixel(static_cast<std::size_t>(rows_) * cols_, -1)
	{
	}
	std::size_t area() const
	{
		return window.empty() ? 0
		                      : static_cast<std::size_t>(width) *
		                            (window.row1 - window.row0);
	}
	/** Index of a cell of the window. */
	std::size_t at(int cy, int cx) const
	{
		return static_cast<std::size_t>(cy - window.row0) * width +
		       (cx - window.col0);
	}
	CellRect window;
	int width;
	std::vector<uint8_t> hit, freeEnd, seenFree;
	std::vector<float> roughSum;
	std::vector<uint16_t> roughN;
	int rows, cols;
	/** Cell index of each pixel (-1: none). */
	std::vector<int> cellOfPixel;
	/** Cells whose labels, roughness or occupancy were updated (their cost
	 * is recomputed). */
	CellRect touched;
	/** Cells whose state, labels, cost or object id changed. */
	CellRect changed;
};

void SemanticMap::insert(
    const Sweep& sweep, const LabeledSweep& ls,
    const mrpt::poses::CPose2D& robotPose)
{
	const mrpt::poses::CPose3D robot(
	    robotPose.x(), robotPose.y(), 0, robotPose.phi(), 0, 0);
	const std::vector<WorldPoint> pts = worldPoints(ls, robot, robotPose);
	SweepEvidence e(
	    sweepWindow(pts, sensorPosition(sweep, robot, robotPose), robotPose),
	    ls.points.rows, ls.points.cols);
	accumulatePoints(pts, ls, e);
	markSeenFree(sweep, robot, robotPose, e);
	updateCells(e);

	// Objects: detections and labelled regions, merged into instances.
	std::vector<int> seenThisSweep, viewedThisSweep;
	countViews(sweep, robot, viewedThisSweep);
	insertDetections(ls, robot, e, seenThisSweep, viewedThisSweep);
	if (m_options.stairsCentroidFromCells)
		for (auto& o : m_instances)
			if (o.label == Label::Stairs &&
			    std::find(seenThisSweep.begin(), seenThisSweep.end(), o.id) !=
			        seenThisSweep.end())
				centreOnCells(o);
	const std::size_t firstNew = m_instances.size();
	insertRegions(ls, robot, pts, e, seenThisSweep);
	countDoorViews(firstNew, seenThisSweep, viewedThisSweep);
	joinDoubleDoors(e.changed);
	keepSweep(sweep, robot);

	// 3D: every point into the OctoMap (endpoints; free space stays 2D).
	if (m_options.octomap) insertIntoOctree(pts);

	// Costs only where this sweep touched, unless the layers may have been
	// written (or loaded) since the last full update.
	updateCostsIn(
	    m_costsCurrent ? e.touched : CellRect::all(m_geometry), e.changed);
	m_costsCurrent = true;
	m_sweeps++;
	markChanged(e.changed, e.touched);
}

void SemanticMap::insertIntoOctree(const std::vector<WorldPoint>& pts)
{
	// Lazy leaf updates, then the inner nodes above the leaves updated
	// (all of them after the tree was written from outside). Points of one
	// voxel: the leaf found once, then the same log-odds update as
	// updateNode() (skipped at the clamping bound).
	std::vector<std::uint64_t> codes;
	codes.reserve(pts.size());
	for (const auto& p : pts)
	{
		octomap::OcTreeKey key;
		if (m_octree->coordToKeyChecked(octomap::point3d(p.x, p.y, p.z), key))
			codes.push_back(mortonCode(key));
	}
	std::sort(codes.begin(), codes.end());
	const bool plain = m_octree->isChangeDetectionEnabled();
	const float hit = m_octree->getProbHitLog();
	const float max = m_octree->getClampingThresMaxLog();
	for (std::size_t b = 0, e = 0; b < codes.size(); b = e)
	{
		const octomap::OcTreeKey key = keyOfCode(codes[b]);
		octomap::OcTreeNode* leaf = m_octree->updateNode(key, true, true);
		for (e = b + 1; e < codes.size() && codes[e] == codes[b]; e++)
			if (plain || !leaf)
				m_octree->updateNode(key, true, true);
			else if (leaf->getLogOdds() < max)
				m_octree->updateNodeLogOdds(leaf, hit);
	}
	if (!m_octreeInnerCurrent)
	{
		m_octree->updateInnerOccupancy();
		m_octreeInnerCurrent = true;
		return;
	}
	codes.erase(std::unique(codes.begin(), codes.end()), codes.end());
	if (m_octree->getRoot() && !codes.empty())
		updateInnerOccupancyAlong(
		    *m_octree, m_octree->getRoot(), 0, codes.data(),
		    codes.data() + codes.size());
}

mrpt::math::TPoint2D SemanticMap::sensorPosition(
    const Sweep& sweep, const mrpt::poses::CPose3D& robot,
    const mrpt::poses::CPose2D& robotPose)
{
	double sx = robotPose.x(), sy = robotPose.y(), sz = 0;
	if (sweep.rows() > 0)
	{
		const auto& sp = sweep.sensorPose(sweep.rows() / 2);
		robot.composePoint(sp.x(), sp.y(), sp.z(), sx, sy, sz);
	}
	return {sx, sy};
}

CellRect SemanticMap::sweepWindow(
    const std::vector<WorldPoint>& pts, const mrpt::math::TPoint2D& sensor,
    const mrpt::poses::CPose2D& robotPose) const
{
	// The points' cells, the rays from the sensor to them, the footprint.
	CellRect w;
	int cx, cy;
	for (const auto& p : pts)
		if (worldToCell(p.x, p.y, cx, cy)) w.add(cy, cx);
	if (worldToCell(sensor.x, sensor.y, cx, cy)) w.add(cy, cx);
	const int rr = static_cast<int>(
	    std::ceil(m_options.robotRadius / m_geometry.resolution));
	if (worldToCell(robotPose.x(), robotPose.y(), cx, cy))
		w = w.united(CellRect{cy - rr, cx - rr, cy + rr + 1, cx + rr + 1});
	return w.clipped(m_geometry);
}

std::vector<SemanticMap::WorldPoint> SemanticMap::worldPoints(
    const LabeledSweep& ls, const mrpt::poses::CPose3D& robot,
    const mrpt::poses::CPose2D& robotPose)
{
	const int rows = ls.points.rows, cols = ls.points.cols;
	std::vector<WorldPoint> pts;
	pts.reserve(static_cast<std::size_t>(rows) * cols);
	double xmin = robotPose.x(), xmax = xmin, ymin = robotPose.y(), ymax = ymin;
	for (int r = 0; r < rows; r++)
		for (int c = 0; c < cols; c++)
		{
			if (!ls.validMask.empty() && !ls.validMask.at<uint8_t>(r, c))
				continue;
			const auto& p = ls.points.at<cv::Vec3f>(r, c);
			if (!std::isfinite(p[0]) || !std::isfinite(p[1]) ||
			    !std::isfinite(p[2]))
				continue;
			double wx, wy, wz;
			robot.composePoint(p[0], p[1], p[2], wx, wy, wz);
			pts.push_back(
			    {static_cast<float>(wx), static_cast<float>(wy),
			     static_cast<float>(wz), static_cast<float>(p[2] - ls.groundZ),
			     r, c});
			xmin = std::min(xmin, wx);
			xmax = std::max(xmax, wx);
			ymin = std::min(ymin, wy);
			ymax = std::max(ymax, wy);
		}
	growToInclude(xmin, ymin, xmax, ymax);
	return pts;
}

void SemanticMap::accumulatePoints(
    const std::vector<WorldPoint>& pts, const LabeledSweep& ls,
    SweepEvidence& e)
{
	const GridGeometry& g = m_geometry;
	const auto& registry = ClassRegistry::instance();
	const LabelSet ground =
	    registry.select([](const ClassInfo& c) { return c.ground; });
	const LabelSet overhead =
	    registry.select([](const ClassInfo& c) { return c.overhead; });
	auto& labelLayer = layer(kLabels);
	auto& stairsLayer = layer(kStairsSweeps);
	std::vector<uint8_t> stairsHere(e.area(), 0);
	for (const auto& p : pts)
	{
		int cx, cy;
		if (!worldToCell(p.x, p.y, cx, cy)) continue;
		const std::size_t i = g.index(cy, cx), j = e.at(cy, cx);
		e.cellOfPixel[static_cast<std::size_t>(p.r) * e.cols + p.c] =
		    static_cast<int>(i);
		const Label l = ls.label(
		    static_cast<std::size_t>(p.r), static_cast<std::size_t>(p.c));
		if (l != Label::Unknown)
		{
			LabelSet s(static_cast<LabelSet::mask_t>(labelLayer[i]));
			s.insert(l);
			if (labelLayer[i] != static_cast<float>(s.mask()))
			{
				e.touched.add(cy, cx);
				e.changed.add(cy, cx);
			}
			labelLayer[i] = static_cast<float>(s.mask());
			if (l == Label::Stairs && !stairsHere[j])
			{
				stairsHere[j] = 1;
				stairsLayer[i] += 1;
			}
		}
		if (ground.contains(l) || p.height < m_options.obstacleMinHeight)
		{
			e.freeEnd[j] = 1;
			if (!ls.roughnessBar.empty())
			{
				const float rb = ls.roughnessBar.at<float>(p.r, p.c);
				if (std::isfinite(rb))
				{
					e.roughSum[j] += rb;
					e.roughN[j]++;
				}
			}
		}
		else if (p.height <= m_options.robotHeight && !overhead.contains(l))
			e.hit[j] = 1;
	}
}

void SemanticMap::markSeenFree(
    const Sweep& sweep, const mrpt::poses::CPose3D& robot,
    const mrpt::poses::CPose2D& robotPose, SweepEvidence& e) const
{
	const GridGeometry& g = m_geometry;
	// Free space: the rays from the sensor to every ground cell seen.
	const mrpt::math::TPoint2D sensor = sensorPosition(sweep, robot, robotPose);
	int scx, scy;
	worldToCell(sensor.x, sensor.y, scx, scy);
	const CellRect& w = e.window;
	for (int cy = w.row0; cy < w.row1; cy++)
		for (int cx = w.col0; cx < w.col1; cx++)
			if (e.freeEnd[e.at(cy, cx)])
				traceLine(
				    scx, scy, cx, cy,
				    [&](int x, int y)
				    {
					    if (w.contains(y, x)) e.seenFree[e.at(y, x)] = 1;
				    });

	// The robot stands on its footprint: free, though the laser cannot
	// see it.
	const int rr =
	    static_cast<int>(std::ceil(m_options.robotRadius / g.resolution));
	int rcx, rcy;
	worldToCell(robotPose.x(), robotPose.y(), rcx, rcy);
	for (int dy = -rr; dy <= rr; dy++)
		for (int dx = -rr; dx <= rr; dx++)
		{
			double x, y;
			if (!cellToWorld(rcx + dx, rcy + dy, x, y)) continue;
			if (std::hypot(x - robotPose.x(), y - robotPose.y()) <=
			    m_options.robotRadius)
				e.seenFree[e.at(rcy + dy, rcx + dx)] = 1;
		}
}

void SemanticMap::updateCells(SweepEvidence& e)
{
	const GridGeometry& g = m_geometry;
	auto& roughLayer = layer(kRoughness);
	auto& obsLayer = layer(kObservations);
	const float pHit = static_cast<float>(m_options.hitProbability);
	const float pFree = static_cast<float>(m_options.freeProbability);
	const CellRect& w = e.window;
	for (int cy = w.row0; cy < w.row1; cy++)
		for (int cx = w.col0; cx < w.col1; cx++)
		{
			const std::size_t i = g.index(cy, cx), j = e.at(cy, cx);
			if (!e.hit[j] && !e.seenFree[j]) continue;
			const CellState before = stateOf(obsLayer[i], cx, cy);
			m_occupancy.updateCell(cx, cy, e.hit[j] ? pHit : pFree);
			obsLayer[i] += 1;
			e.touched.add(cy, cx);
			if (stateOf(obsLayer[i], cx, cy) != before) e.changed.add(cy, cx);
			if (e.roughN[j])
			{
				const float mean = e.roughSum[j] / e.roughN[j];
				const float prev = roughLayer[i];
				roughLayer[i] = std::isnan(prev) ? mean : 0.5f * (prev + mean);
			}
		}
}

void SemanticMap::paintObject(
    SweepEvidence& e, int id, const cv::Rect& box,
    const std::function<bool(int, int)>& belongs)
{
	auto& objLayer = layer(kObjects);
	const cv::Rect clip = box & cv::Rect(0, 0, e.cols, e.rows);
	for (int r = clip.y; r < clip.y + clip.height; r++)
		for (int c = clip.x; c < clip.x + clip.width; c++)
		{
			const int i =
			    e.cellOfPixel[static_cast<std::size_t>(r) * e.cols + c];
			if (i < 0 || !belongs(r, c)) continue;
			float& cell = objLayer[static_cast<std::size_t>(i)];
			if (cell != static_cast<float>(id))
				e.changed.add(i / m_geometry.cols, i % m_geometry.cols);
			cell = static_cast<float>(id);
		}
}

void SemanticMap::insertDetections(
    const LabeledSweep& ls, const mrpt::poses::CPose3D& robot, SweepEvidence& e,
    std::vector<int>& seenThisSweep, std::vector<int>& viewedThisSweep)
{
	for (const auto& d : ls.detections)
	{
		const mrpt::math::TPoint3D half{
		    d.extent.x / 2, d.extent.y / 2, d.extent.z / 2};
		const mrpt::math::TBoundingBox box =
		    toWorldBox(robot, d.centroid - half, d.centroid + half);
		mrpt::math::TPoint3D wc;
		robot.composePoint(d.centroid, wc);
		int id = 0;
		// By value: MRPT packs TPoint3D, so a double& to its members is
		// misaligned (UBSan).
		const double ex = d.extent.x, ey = d.extent.y;
		mergeObject(
		    d.label, wc, {std::max(ex, ey), 0, d.extent.z}, box, d.shapeScore,
		    seenThisSweep, id);
		if (ObjectInstance* o = instanceWithId(id))
			countDetectedView(*o, viewedThisSweep);
		paintObject(
		    e, id, d.imageBox,
		    [&](int r, int c)
		    {
			    return ls.label(
			               static_cast<std::size_t>(r),
			               static_cast<std::size_t>(c)) == d.label;
		    });
	}
}

void SemanticMap::insertRegions(
    const LabeledSweep& ls, const mrpt::poses::CPose3D& robot,
    const std::vector<WorldPoint>& pts, SweepEvidence& e,
    std::vector<int>& seenThisSweep)
{
	const auto& registry = ClassRegistry::instance();
	const std::vector<mrpt::math::TBoundingBox> pointBoxes =
	    m_options.doorFootprintFromPoints
	        ? regionPointBoxes(ls, pts)
	        : std::vector<mrpt::math::TBoundingBox>();
	// Per instance given a sighting in this sweep: that region's pixels.
	std::map<int, std::size_t> sightingPixels;
	for (const auto& reg : ls.regions)
	{
		if (!registry.contains(reg.label) ||
		    classInfo(reg.label).instances !=
		        ClassInfo::InstanceSource::Regions)
			continue;
		// Floor to ceiling: a wall the rules took for a door.
		if (m_options.doorRegionMaxHeight > 0 &&
		    reg.height > m_options.doorRegionMaxHeight)
			continue;
		const std::size_t k = static_cast<std::size_t>(reg.id);
		const mrpt::math::TBoundingBox box =
		    reg.id >= 0 && k < pointBoxes.size() &&
		            pointBoxes[k].min.x <= pointBoxes[k].max.x
		        ? pointBoxes[k]
		        : toWorldBox(robot, reg.minCorner, reg.maxCorner);
		mrpt::math::TPoint3D wc;
		// A region's box is centred on a flat leaf however it is seen; the
		// mean of its points leans to its near side.
		const mrpt::math::TPoint3D at =
		    m_options.doorSightingBoxCentreMinWidth > 0 &&
		            reg.width >= m_options.doorSightingBoxCentreMinWidth &&
		            (m_options.doorSightingBoxCentreMaxWidth <= 0 ||
		             reg.width <= m_options.doorSightingBoxCentreMaxWidth)
		        ? doorRegionMiddle(
		              ls, reg, m_options.doorSightingFullHeightShare)
		        : reg.centroid;
		robot.composePoint(at, wc);
		const std::size_t before = seenThisSweep.size();
		int id = 0;
		const mrpt::math::TPoint3D size{reg.width, 0, reg.height};
		mergeObject(
		    reg.label, wc, size, box, doorLeafScore(reg), seenThisSweep, id);
		if (ObjectInstance* o = instanceWithId(id))
		{
			addNormal(robot, reg.meanNormal, *o);
			if (seenThisSweep.size() > before)  // it gave the sighting
				sightingPixels[id] = reg.pixels;
			else if (
			    m_options.doorSightingLargestRegion && o->leaves == 1 &&
			    reg.pixels > sightingPixels[id])
			{
				o->replaceLastSighting(
				    wc, size, m_options.mergeDistance / 2,
				    sightingMaxWeightWidth(reg.label));
				sightingPixels[id] = reg.pixels;
			}
		}
		paintObject(
		    e, id, reg.imageBox,
		    [&](int r, int c)
		    { return ls.regionIds.at<int32_t>(r, c) == reg.id; });
	}
}

double SemanticMap::sightingMaxWeightWidth(Label label) const
{
	return classInfo(label).instances == ClassInfo::InstanceSource::Regions
	           ? m_options.doorCentroidMaxWeightWidth
	           : 0;
}

void SemanticMap::mergeObject(
    Label label, const mrpt::math::TPoint3D& centroid,
    const mrpt::math::TPoint3D& size, const mrpt::math::TBoundingBox& box,
    double shapeScore, std::vector<int>& seenThisSweep, int& id)
{
	// The nearest instance of the label within mergeDistance or whose
	// footprint overlaps the detection's (classes merged by sighting, e.g.
	// washbasins: within objectMergeDistance of one of its sightings).
	const bool byFootprint =
	    classInfo(label).merge == ClassInfo::Merge::ByFootprint;
	ObjectInstance* best = nullptr;
	double bestD = std::numeric_limits<double>::infinity();
	for (auto& o : m_instances)
	{
		if (o.label != label) continue;
		const double d =
		    std::hypot(o.centroid.x - centroid.x, o.centroid.y - centroid.y);
		bool joins;
		if (byFootprint)
			joins = d < m_options.mergeDistance || o.footprintOverlaps(box);
		else
		{
			double nearest = d;
			for (const auto& s : o.sightings)
				nearest = std::min(
				    nearest, std::hypot(s.x - centroid.x, s.y - centroid.y));
			joins = nearest < m_options.objectMergeDistance;
		}
		if (joins && d < bestD)
		{
			bestD = d;
			best = &o;
		}
	}
	if (!best)
	{
		ObjectInstance o;
		// Ids stay unique when a joined double door took an instance out.
		o.id = 1;
		for (const auto& other : m_instances)
			o.id = std::max(o.id, other.id + 1);
		o.label = label;
		o.centroid = centroid;
		o.sightings.push_back(centroid);
		o.sightingSizes.push_back(size);
		o.minCorner = box.min;
		o.maxCorner = box.max;
		o.observations = 1;
		o.bestShapeScore = shapeScore;
		m_instances.push_back(o);
		seenThisSweep.push_back(o.id);
		id = o.id;
		return;
	}
	const bool again =
	    std::find(seenThisSweep.begin(), seenThisSweep.end(), best->id) !=
	    seenThisSweep.end();
	if (!again)
	{
		const mrpt::math::TPoint3D middle = best->centroid;
		best->sightingSizes.push_back(size);
		best->addSighting(
		    centroid, m_options.mergeDistance / 2,
		    sightingMaxWeightWidth(label));
		if (best->leaves == 2) centreOnLeaves(*best, middle);
		best->observations++;
		seenThisSweep.push_back(best->id);
	}
	best->bestShapeScore = std::max(best->bestShapeScore, shapeScore);
	best->takeInBox(box);
	id = best->id;
}

}  // namespace semnav
