/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/ClassRegistry.h>
#include <semnav/common/OptionTable.h>
#include <semnav/localization/ObjectFootprints.h>
#include <semnav/localization/WallMap.h>
#include <semnav/perception/LabeledSweep.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <unordered_map>
#include <unordered_set>

namespace semnav
{
namespace
{
using O = ObjectFootprints::TOptions;
const OptionTable<O>& optionTable()
{
	static const auto t =
	    OptionTable<O>()
	        .real(
	            "points", &O::points, 0, 1000,
	            "Mapping: weight of the object footprints (posts, bins) "
	            "against the landmarks of earlier sweeps, in effective "
	            "points; 0: off.")
	        .real(
	            "sigma_m", &O::sigma, 0.01, 10,
	            "Std dev of a footprint's distance to the nearest "
	            "landmark...")
	        .real(
	            "max_distance_m", &O::maxDistance, 0.01, 100,
	            "...clamped here.")
	        .real(
	            "gate_m", &O::gate, 0.01, 100,
	            "Footprints farther than this from every landmark at the "
	            "predicted pose are not scored (new objects).")
	        .real(
	            "hit_weight", &O::hitWeight, 0, 1,
	            "Mixture weight of the Gaussian part...")
	        .real(
	            "random_weight", &O::randomWeight, 1e-6, 1,
	            "...and of the uniform part.")
	        .real(
	            "cell_m", &O::cell, 0.01, 1,
	            "Obstacle points are clustered on a grid of this cell.")
	        .real(
	            "max_width_m", &O::maxWidth, 0.01, 10,
	            "Wider clusters are no compact object.")
	        .real(
	            "min_width_m", &O::minWidth, 0, 10,
	            "Narrower clusters (across the ray) are edges of something "
	            "seen side-on.")
	        .real(
	            "min_height_m", &O::minHeight, 0, 10,
	            "Lower clusters (above the ground) are left out.")
	        .integer(
	            "min_points", &O::minPoints, 1, 100000,
	            "Clusters with fewer points are left out.")
	        .real(
	            "max_bottom_m", &O::maxBottom, 0, 10,
	            "Clusters whose lowest point is higher above the ground are "
	            "left out (table tops).")
	        .real(
	            "clearance_m", &O::clearance, 0, 10,
	            "Clusters with a wall or door point, or another cluster, this "
	            "close are left out.")
	        .real(
	            "max_range_m", &O::maxRange, 0.5, 100,
	            "Farther clusters are left out.")
	        .real(
	            "associate_m", &O::associate, 0.01, 10,
	            "A footprint this close to a landmark joins it.")
	        .integer(
	            "min_sweeps", &O::minSweeps, 1, 1000,
	            "A landmark is scored once seen from this many sweeps.");
	return t;
}

/** Labels whose points may belong to a compact object. */
bool isObjectLabel(Label l)
{
	if (l == Label::Obstacle) return true;
	const ClassInfo& c = classInfo(l);
	return c.hasInstances() && !c.structure &&
	       c.passage == ClassInfo::Passage::Blocking;
}

/** Labels of walls and doors (not the ceiling). */
bool isStructureLabel(Label l)
{
	const ClassInfo& c = classInfo(l);
	return c.structure && !c.overhead;
}

using CellKey = long long;
/** Both cell indices in one key (negative ones too: the shift is unsigned). */
CellKey cellKey(long cx, long cy)
{
	const auto hi = static_cast<unsigned long long>(cx) << 32;
	const auto lo = static_cast<unsigned long long>(cy) & 0xffffffffULL;
	return static_cast<CellKey>(hi ^ lo);
}

int findRoot(std::vector<int>& parent, int i)
{
	while (parent[i] != i) i = parent[i] = parent[parent[i]];
	return i;
}

struct Cluster
{
	std::vector<mrpt::math::TPoint2D> points;
	std::vector<std::pair<long, long>> cells;
	double zMin = std::numeric_limits<double>::infinity();
	double zMax = -std::numeric_limits<double>::infinity();
};

/** The object points of a sweep on a grid of `cell`, 8-connected into
 * clusters; `structure` gets the cells holding wall or door points. */
std::vector<Cluster> clusterObjectPoints(
    const LabeledSweep& s, double cell, double reach,
    std::unordered_set<CellKey>& structure)
{
	const double inv = 1.0 / cell;
	std::unordered_map<CellKey, int> cellIndex;
	std::vector<Cluster> cells;
	for (int r = 0; r < s.labels.rows; r++)
		for (int c = 0; c < s.labels.cols; c++)
		{
			const Label l = s.label(r, c);
			const bool object = isObjectLabel(l);
			if (!object && !isStructureLabel(l)) continue;
			const auto& p = s.points.at<cv::Vec3f>(r, c);
			if (!std::isfinite(p[0]) || std::hypot(p[0], p[1]) > reach)
				continue;
			const long cx = static_cast<long>(std::floor(p[0] * inv));
			const long cy = static_cast<long>(std::floor(p[1] * inv));
			if (!object)
			{
				structure.insert(cellKey(cx, cy));
				continue;
			}
			auto [it, added] = cellIndex.emplace(
			    cellKey(cx, cy), static_cast<int>(cells.size()));
			if (added) cells.push_back({{}, {{cx, cy}}});
			Cluster& dst = cells[it->second];
			dst.points.push_back({p[0], p[1]});
			dst.zMin = std::min(dst.zMin, double(p[2]));
			dst.zMax = std::max(dst.zMax, double(p[2]));
		}
	std::vector<int> parent(cells.size());
	std::iota(parent.begin(), parent.end(), 0);
	for (std::size_t i = 0; i < cells.size(); i++)
		for (long dx = -1; dx <= 1; dx++)
			for (long dy = -1; dy <= 1; dy++)
			{
				const auto [cx, cy] = cells[i].cells.front();
				const auto n = cellIndex.find(cellKey(cx + dx, cy + dy));
				if (n == cellIndex.end()) continue;
				parent[findRoot(parent, static_cast<int>(i))] =
				    findRoot(parent, n->second);
			}
	std::vector<Cluster> clusters(cells.size());
	for (std::size_t i = 0; i < cells.size(); i++)
	{
		Cluster& dst = clusters[findRoot(parent, static_cast<int>(i))];
		const Cluster& src = cells[i];
		dst.points.insert(
		    dst.points.end(), src.points.begin(), src.points.end());
		dst.cells.push_back(src.cells.front());
		dst.zMin = std::min(dst.zMin, src.zMin);
		dst.zMax = std::max(dst.zMax, src.zMax);
	}
	clusters.erase(
	    std::remove_if(
	        clusters.begin(), clusters.end(),
	        [](const Cluster& c) { return c.points.empty(); }),
	    clusters.end());
	return clusters;
}

/** True when a structure cell or another cluster's cell lies within k
 * cells of the cluster's (a wall fragment, a piece of a larger object). */
bool crowded(
    const Cluster& cl, int id, const std::unordered_set<CellKey>& structure,
    const std::unordered_map<CellKey, int>& owner, long k)
{
	for (const auto& [cx, cy] : cl.cells)
		for (long dx = -k; dx <= k; dx++)
			for (long dy = -k; dy <= k; dy++)
			{
				const CellKey key = cellKey(cx + dx, cy + dy);
				const auto o = owner.find(key);
				if (structure.count(key) ||
				    (o != owner.end() && o->second != id))
					return true;
			}
	return false;
}
}  // namespace

SEMNAV_OPTIONS_FROM_TABLE(ObjectFootprints::TOptions, optionTable())

std::vector<ObjectFootprints::Footprint> ObjectFootprints::extract(
    const LabeledSweep& s) const
{
	std::unordered_set<CellKey> structure;
	const std::vector<Cluster> clusters = clusterObjectPoints(
	    s, m_options.cell, m_options.maxRange + m_options.maxWidth, structure);
	const long k =
	    static_cast<long>(std::ceil(m_options.clearance / m_options.cell));
	std::unordered_map<CellKey, int> owner;
	for (std::size_t i = 0; i < clusters.size(); i++)
		for (const auto& [cx, cy] : clusters[i].cells)
			owner[cellKey(cx, cy)] = static_cast<int>(i);
	std::vector<Footprint> out;
	for (std::size_t i = 0; i < clusters.size(); i++)
	{
		const Cluster& cl = clusters[i];
		if (static_cast<int>(cl.points.size()) < m_options.minPoints ||
		    cl.zMax - s.groundZ < m_options.minHeight ||
		    cl.zMin - s.groundZ > m_options.maxBottom ||
		    crowded(cl, static_cast<int>(i), structure, owner, k))
			continue;
		double mx = 0, my = 0;
		for (const auto& p : cl.points) mx += p.x, my += p.y;
		mx /= double(cl.points.size()), my /= double(cl.points.size());
		const double range = std::hypot(mx, my);
		if (range > m_options.maxRange || range < 1e-3) continue;
		// Extents across and along the ray to the centroid.
		const double ux = mx / range, uy = my / range;
		double a0 = 1e9, a1 = -1e9, b0 = 1e9, b1 = -1e9;
		for (const auto& p : cl.points)
		{
			const double across = -uy * (p.x - mx) + ux * (p.y - my);
			const double along = ux * (p.x - mx) + uy * (p.y - my);
			a0 = std::min(a0, across), a1 = std::max(a1, across);
			b0 = std::min(b0, along), b1 = std::max(b1, along);
		}
		if (a1 - a0 > m_options.maxWidth || b1 - b0 > m_options.maxWidth ||
		    a1 - a0 < m_options.minWidth)
			continue;
		Footprint f;
		f.radius = 0.5 * (a1 - a0);
		const double shift = M_PI / 4 * f.radius;
		f.x = mx + ux * shift, f.y = my + uy * shift;
		out.push_back(f);
	}
	return out;
}

int ObjectFootprints::nearest(
    double wx, double wy, bool establishedOnly, double maxD, double& d) const
{
	int best = -1;
	d = maxD;
	for (std::size_t i = 0; i < m_landmarks.size(); i++)
	{
		const Footprint& l = m_landmarks[i];
		if (establishedOnly && l.sweeps < m_options.minSweeps) continue;
		const double di = std::hypot(l.x - wx, l.y - wy);
		if (di <= d) d = di, best = static_cast<int>(i);
	}
	return best;
}

void ObjectFootprints::insert(
    const std::vector<Footprint>& footprints, const mrpt::poses::CPose2D& pose)
{
	const std::size_t before = m_landmarks.size();
	for (const Footprint& f : footprints)
	{
		mrpt::math::TPoint2D w;
		pose.composePoint(f.x, f.y, w.x, w.y);
		double d = 0;
		const int i = nearest(w.x, w.y, false, m_options.associate, d);
		// One sweep adds to a landmark at most once; landmarks it makes
		// are not joined by its own other footprints.
		if (i < 0 || static_cast<std::size_t>(i) >= before)
		{
			m_landmarks.push_back({w.x, w.y, f.radius, 1});
			m_sums.push_back(w);
			continue;
		}
		Footprint& l = m_landmarks[static_cast<std::size_t>(i)];
		auto& sum = m_sums[static_cast<std::size_t>(i)];
		sum.x += w.x, sum.y += w.y;
		l.sweeps++;
		l.x = sum.x / l.sweeps, l.y = sum.y / l.sweeps;
		l.radius = std::max(l.radius, f.radius);
	}
}

std::vector<SemanticSample> ObjectFootprints::observedPart(
    double x, double y, double yaw,
    const std::vector<Footprint>& footprints) const
{
	std::vector<SemanticSample> out;
	const mrpt::poses::CPose2D pose(x, y, yaw);
	for (const Footprint& f : footprints)
	{
		mrpt::math::TPoint2D w;
		pose.composePoint(f.x, f.y, w.x, w.y);
		double d = 0;
		if (nearest(w.x, w.y, true, m_options.gate, d) >= 0)
			out.push_back(
			    {static_cast<float>(f.x), static_cast<float>(f.y),
			     Label::Obstacle});
	}
	return out;
}

double ObjectFootprints::logLikelihood(
    double x, double y, double yaw,
    const std::vector<SemanticSample>& footprints) const
{
	if (footprints.empty() || !m_options.enabled()) return 0;
	const double c = std::cos(yaw), s = std::sin(yaw);
	double sum = 0;
	for (const SemanticSample& f : footprints)
	{
		double d = 0;
		nearest(
		    x + c * f.x - s * f.y, y + s * f.x + c * f.y, true,
		    m_options.maxDistance, d);
		sum += WallMap::mixtureLogLikelihood(
		    d, m_options.sigma, m_options.maxDistance, m_options.hitWeight,
		    m_options.randomWeight);
	}
	return m_options.points * sum / double(footprints.size());
}

}  // namespace semnav
