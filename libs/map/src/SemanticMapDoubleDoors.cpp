/* semnav: semantic navigation from tilting-laser sweeps */
// SemanticMap::insert(), double doors: the rules find a double door leaf by
// leaf, so two door instances side by side in one wall become one door at
// their middle (TOptions::doubleDoorMaxWidth).
#include <semnav/common/ClassRegistry.h>
#include <semnav/common/LabelSet.h>
#include <semnav/map/SemanticMap.h>

#include <algorithm>
#include <cmath>

namespace semnav
{
namespace
{
/** Unit horizontal normal of a door, false when unknown. */
bool unitNormal(const ObjectInstance& o, double& nx, double& ny)
{
	const double n = std::hypot(o.normalSum.x, o.normalSum.y);
	if (n < 1e-9) return false;
	nx = o.normalSum.x / n;
	ny = o.normalSum.y / n;
	return true;
}

/** Whether two doors' normals are parallel within 15 deg, either way (a
 * door seen from both sides); (nx, ny): their mean unit normal. */
bool parallelDoors(
    const ObjectInstance& a, const ObjectInstance& b, double& nx, double& ny)
{
	double ax, ay, bx, by;
	if (!unitNormal(a, ax, ay) || !unitNormal(b, bx, by)) return false;
	constexpr double kMaxAngleDeg = 15;
	const double dot = ax * bx + ay * by;
	if (std::abs(dot) < std::cos(kMaxAngleDeg * M_PI / 180)) return false;
	const double s = dot < 0 ? -1 : 1;
	nx = ax + s * bx;
	ny = ay + s * by;
	const double nn = std::hypot(nx, ny);
	nx /= nn;
	ny /= nn;
	return true;
}

/** The distance of b's centroid from a's plane of normal (nx, ny). */
double planeOffset(
    const ObjectInstance& a, const ObjectInstance& b, double nx, double ny)
{
	return std::abs(
	    (b.centroid.x - a.centroid.x) * nx +
	    (b.centroid.y - a.centroid.y) * ny);
}

/** The extent of a footprint box along the direction (tx, ty). */
void spanAlong(
    const ObjectInstance& o, double tx, double ty, double& lo, double& hi)
{
	lo = 1e18;
	hi = -1e18;
	for (int k = 0; k < 4; k++)
	{
		const double x = (k & 1) ? o.maxCorner.x : o.minCorner.x;
		const double y = (k & 2) ? o.maxCorner.y : o.minCorner.y;
		lo = std::min(lo, x * tx + y * ty);
		hi = std::max(hi, x * tx + y * ty);
	}
}
}  // namespace

double SemanticMap::longestWallBetween(
    const mrpt::math::TPoint3D& a, const mrpt::math::TPoint3D& b) const
{
	const auto& labels = get(kLabels);
	const double len = std::hypot(b.x - a.x, b.y - a.y);
	const double step = m_geometry.resolution / 2;
	const int n = std::max(1, static_cast<int>(std::ceil(len / step)));
	double longest = 0, run = 0;
	for (int k = 0; k <= n; k++)
	{
		const double t = static_cast<double>(k) / n;
		int cx, cy;
		bool wall = false;
		if (worldToCell(a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), cx, cy))
		{
			const LabelSet ls(static_cast<LabelSet::mask_t>(
			    labels[m_geometry.index(cy, cx)]));
			wall = ls.contains(Label::Wall) && !ls.contains(Label::Door);
		}
		run = wall ? run + len / n : 0;
		longest = std::max(longest, run);
	}
	return longest;
}

bool SemanticMap::leavesOfOneDoor(
    const ObjectInstance& a, const ObjectInstance& b) const
{
	double nx, ny;
	// Two doors the map reports (a one-off fragment is no leaf), in one
	// plane.
	if (a.leaves != 1 || b.leaves != 1 || !reported(a) || !reported(b) ||
	    !parallelDoors(a, b, nx, ny))
		return false;
	const double offset = planeOffset(a, b, nx, ny);
	if (offset > m_options.doubleDoorMaxPlaneOffset ||
	    (m_options.doubleDoorMaxLeafOffset > 0 &&
	     offset > m_options.doubleDoorMaxLeafOffset))
		return false;
	// Each a leaf, alike, together a double door.
	const double wa = a.typicalSize().x, wb = b.typicalSize().x;
	if (wa > m_options.doubleDoorMaxLeafWidth ||
	    wb > m_options.doubleDoorMaxLeafWidth ||
	    std::min(wa, wb) <
	        m_options.doubleDoorMinLeafWidthRatio * std::max(wa, wb))
		return false;
	const double tx = -ny, ty = nx;
	double alo, ahi, blo, bhi;
	spanAlong(a, tx, ty, alo, ahi);
	spanAlong(b, tx, ty, blo, bhi);
	if (std::max(ahi, bhi) - std::min(alo, blo) > m_options.doubleDoorMaxWidth)
		return false;
	// No wall between them: two rooms' doors have one.
	return longestWallBetween(a.centroid, b.centroid) <=
	       m_options.doubleDoorMaxWall;
}

bool SemanticMap::duplicatesOfOneDoor(
    const ObjectInstance& a, const ObjectInstance& b) const
{
	double nx, ny;
	if (m_options.doorJoinDistance <= 0 || a.leaves != 1 || b.leaves != 1 ||
	    !reported(a) || !reported(b) ||
	    std::hypot(b.centroid.x - a.centroid.x, b.centroid.y - a.centroid.y) >
	        m_options.doorJoinDistance ||
	    !parallelDoors(a, b, nx, ny) ||
	    planeOffset(a, b, nx, ny) > m_options.doubleDoorMaxPlaneOffset)
		return false;
	return a.footprintOverlaps(b.box());
}

bool SemanticMap::pieceOfDoor(
    const ObjectInstance& whole, const ObjectInstance& part) const
{
	double nx, ny;
	if (m_options.doorJoinContainedShare <= 0 || whole.leaves != 1 ||
	    part.leaves != 1 || part.observations > whole.observations ||
	    !reported(whole) || !reported(part) ||
	    std::hypot(
	        part.centroid.x - whole.centroid.x,
	        part.centroid.y - whole.centroid.y) >
	        m_options.doubleDoorMaxWidth ||
	    !parallelDoors(whole, part, nx, ny) ||
	    planeOffset(whole, part, nx, ny) > m_options.doubleDoorMaxPlaneOffset)
		return false;
	// The piece's span along the wall, inside the door's.
	double wlo, whi, plo, phi;
	spanAlong(whole, -ny, nx, wlo, whi);
	spanAlong(part, -ny, nx, plo, phi);
	const double inside = std::min(whi, phi) - std::max(wlo, plo);
	return phi > plo &&
	       inside >= m_options.doorJoinContainedShare * (phi - plo);
}

void SemanticMap::absorbDoor(ObjectInstance& a, int bIndex, CellRect& changed)
{
	const ObjectInstance& b = m_instances[static_cast<std::size_t>(bIndex)];
	// Both instances' sightings, footprints and normals; the larger counts
	// (a sweep may have detected both).
	a.sightings.insert(
	    a.sightings.end(), b.sightings.begin(), b.sightings.end());
	a.sightingSizes.insert(
	    a.sightingSizes.end(), b.sightingSizes.begin(), b.sightingSizes.end());
	a.takeInBox(b.box());
	const double sign =
	    a.normalSum.x * b.normalSum.x + a.normalSum.y * b.normalSum.y < 0 ? -1
	                                                                      : 1;
	a.normalSum = a.normalSum + b.normalSum * sign;
	a.observations = std::max(a.observations, b.observations);
	a.views = std::max(a.views, b.views);
	a.bestShapeScore = std::max(a.bestShapeScore, b.bestShapeScore);
	const int from = b.id, to = a.id;
	m_instances.erase(m_instances.begin() + bIndex);
	auto& objs = layer(kObjects);
	for (int cy = 0; cy < m_geometry.rows; cy++)
		for (int cx = 0; cx < m_geometry.cols; cx++)
		{
			float& v = objs[m_geometry.index(cy, cx)];
			if (v != static_cast<float>(from)) continue;
			v = static_cast<float>(to);
			changed.add(cy, cx);
		}
}

void SemanticMap::joinDoubleDoors(CellRect& changed)
{
	if (m_options.doubleDoorMaxWidth <= 0 && m_options.doorJoinDistance <= 0)
		return;
	const auto isDoor = [](const ObjectInstance& o) {
		return classInfo(o.label).instances ==
		       ClassInfo::InstanceSource::Regions;
	};
	for (bool joined = true; joined;)
	{
		joined = false;
		for (std::size_t i = 0; i < m_instances.size() && !joined; i++)
			for (std::size_t j = i + 1; j < m_instances.size() && !joined; j++)
			{
				ObjectInstance &a = m_instances[i], &b = m_instances[j];
				if (!isDoor(a) || b.label != a.label) continue;
				mrpt::math::TPoint3D c;
				int leaves = 1;
				if (m_options.doubleDoorMaxWidth > 0 && leavesOfOneDoor(a, b))
				{
					// The middle of the two leaves.
					c = (a.centroid + b.centroid) * 0.5;
					leaves = 2;
				}
				else if (duplicatesOfOneDoor(a, b))
				{
					// One door found twice: the mean of the two weighted by
					// their detections.
					const double wa = static_cast<double>(a.observations),
					             wb = static_cast<double>(b.observations);
					c = (a.centroid * wa + b.centroid * wb) * (1.0 / (wa + wb));
				}
				else if (pieceOfDoor(a, b))
					c = a.centroid;  // b is a piece of door a
				else if (pieceOfDoor(b, a))
					c = b.centroid;
				else
					continue;
				absorbDoor(a, static_cast<int>(j), changed);
				a.centroid = c;
				a.leaves = leaves;
				joined = true;
			}
	}
}

void SemanticMap::centreOnLeaves(
    ObjectInstance& o, const mrpt::math::TPoint3D& middle)
{
	double nx, ny;
	if (!unitNormal(o, nx, ny)) return;
	const double tx = -ny, ty = nx;
	mrpt::math::TPoint3D sum[2] = {{0, 0, 0}, {0, 0, 0}};
	int count[2] = {0, 0};
	for (const auto& s : o.sightings)
	{
		const int side =
		    (s.x - middle.x) * tx + (s.y - middle.y) * ty < 0 ? 0 : 1;
		sum[side] = sum[side] + s;
		count[side]++;
	}
	if (!count[0] || !count[1])
	{
		o.centroid = middle;
		return;
	}
	o.centroid = (sum[0] * (1.0 / count[0]) + sum[1] * (1.0 / count[1])) * 0.5;
}

}  // namespace semnav
