/* semnav: semantic navigation from tilting-laser sweeps */
// SemanticMap: a staircase's centroid from the cells labelled stairs
// (TOptions::stairsCentroidFromCells).
#include <semnav/common/ClassRegistry.h>
#include <semnav/map/SemanticMap.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

namespace semnav
{
namespace
{
using Cell = std::pair<int, int>;

/** The unit axis of a flight (across its risers, in cells): the direction
 * along which its cells' projections are most peaked. Seen from its foot, a
 * flight's labelled cells are rows along its risers, so projected across
 * them they pile up in a few bins. {0, 0} for too few cells. */
std::pair<double, double> flightAxis(const std::vector<Cell>& cells)
{
	constexpr std::size_t kMinCells = 20;
	if (cells.size() < kMinCells) return {0, 0};
	constexpr int kSteps = 36;  // 5 deg
	double bestScore = -1, bestX = 0, bestY = 0;
	for (int i = 0; i < kSteps; i++)
	{
		const double a = M_PI * i / kSteps;
		const double nx = -std::sin(a), ny = std::cos(a);
		std::map<long, double> bins;
		for (const auto& [cx, cy] : cells)
			bins[std::lround(cx * nx + cy * ny)] += 1;
		double score = 0;
		for (const auto& [k, n] : bins) score += n * n;
		if (score > bestScore)
		{
			bestScore = score;
			bestX = nx;
			bestY = ny;
		}
	}
	return {bestX, bestY};
}

/** The cells of the row through (cx, cy) along the risers of a flight of
 * axis (ax, ay) for which `flight` holds, one-cell gaps allowed: a riser is
 * a row, a chair's legs or a stray cell in front of the flight are not. */
template <typename F>
int rowLength(int cx, int cy, double ax, double ay, const F& flight)
{
	int n = 0;
	for (const int sign : {-1, 1})
		for (int s = sign > 0 ? 1 : 0, misses = 0; misses < 2; s++)
		{
			const int x = cx + static_cast<int>(std::lround(-sign * s * ay));
			const int y = cy + static_cast<int>(std::lround(sign * s * ax));
			if (flight(x, y))
			{
				n++;
				misses = 0;
			}
			else
				misses++;
		}
	return n;
}

/** The middle (world x, y) of the bounding box of non-empty `cells`. */
std::pair<double, double> middleOfCells(
    const std::vector<Cell>& cells, const GridGeometry& g)
{
	int x0 = cells[0].first, x1 = x0, y0 = cells[0].second, y1 = y0;
	for (const auto& [cx, cy] : cells)
	{
		x0 = std::min(x0, cx);
		x1 = std::max(x1, cx);
		y0 = std::min(y0, cy);
		y1 = std::max(y1, cy);
	}
	return {
	    0.5 * (g.centerX(x0) + g.centerX(x1)),
	    0.5 * (g.centerY(y0) + g.centerY(y1))};
}
}  // namespace

void SemanticMap::centreOnCells(ObjectInstance& o) const
{
	const GridGeometry& g = m_geometry;
	const auto& labels = get(kLabels);
	// The footprint (and its margin).
	int x0, y0, x1, y1;
	const double margin = m_options.stairsCellMargin;
	worldToCell(o.minCorner.x - margin, o.minCorner.y - margin, x0, y0);
	worldToCell(o.maxCorner.x + margin, o.maxCorner.y + margin, x1, y1);
	x0 = std::max(x0, 0);
	y0 = std::max(y0, 0);
	x1 = std::min(x1, g.cols - 1);
	y1 = std::min(y1, g.rows - 1);
	if (x1 < x0 || y1 < y0) return;
	const auto inFootprint = [&](int cx, int cy)
	{ return cx >= x0 && cx <= x1 && cy >= y0 && cy <= y1; };
	// A wall, or an object beside the flight that a false stairs detection
	// took in (a class whose sightings merge one by one), is no part of it.
	LabelSet notFlight = ClassRegistry::instance().select(
	    [](const ClassInfo& c)
	    {
		    return c.instances == ClassInfo::InstanceSource::Detections &&
		           c.merge == ClassInfo::Merge::BySighting;
	    });
	notFlight.insert(Label::Wall);
	const auto labelled = [&](int cx, int cy)
	{
		const LabelSet ls(
		    static_cast<LabelSet::mask_t>(labels[g.index(cy, cx)]));
		return ls.contains(Label::Stairs) &&
		       (ls.mask() & notFlight.mask()) == 0;
	};
	// Cells labelled in too few sweeps, against the footprint's most
	// labelled one, are no part of the flight (a map saved without the
	// counts loads them as 0: every labelled cell counts).
	const auto& sweeps = get(kStairsSweeps);
	float most = 0;
	std::vector<Cell> labelledCells;
	for (int cy = y0; cy <= y1; cy++)
		for (int cx = x0; cx <= x1; cx++)
			if (labelled(cx, cy))
			{
				labelledCells.emplace_back(cx, cy);
				most = std::max(most, sweeps[g.index(cy, cx)]);
			}
	const float least =
	    std::max(1.0f, static_cast<float>(m_options.stairsMinCellShare) * most);
	const auto enoughSweeps = [&](int cx, int cy)
	{ return most <= 0 || sweeps[g.index(cy, cx)] >= least; };
	const auto stairs = [&](int cx, int cy)
	{ return labelled(cx, cy) && enoughSweeps(cx, cy); };
	std::vector<Cell> inside;
	for (const auto& [cx, cy] : labelledCells)
		if (enoughSweeps(cx, cy)) inside.emplace_back(cx, cy);
	const auto [ax, ay] = m_options.stairsRiserGap > 0
	                          ? flightAxis(inside)
	                          : std::pair<double, double>{0, 0};
	const bool axisKnown = ax != 0 || ay != 0;

	// Seeds: stairs cells within half the merge distance of a sighting
	// that is no outlier (one farther than the merge distance from the
	// sightings' median joined by footprint overlap only: a detection of
	// a table beside the flight).
	const int w = x1 - x0 + 1;
	std::vector<uint8_t> mark(static_cast<std::size_t>(w) * (y1 - y0 + 1), 0);
	std::vector<Cell> queue;
	const auto take = [&](int cx, int cy)
	{
		auto& m = mark[static_cast<std::size_t>(cy - y0) * w + cx - x0];
		if (m || !stairs(cx, cy)) return;
		m = 1;
		queue.emplace_back(cx, cy);
	};
	const double reach = m_options.mergeDistance / 2;
	auto seeds = o.inlierSightings(m_options.mergeDistance);
	if (seeds.empty()) seeds.push_back(o.centroid);
	for (const auto& s : seeds)
		for (const auto& [cx, cy] : inside)
			if (std::hypot(g.centerX(cx) - s.x, g.centerY(cy) - s.y) <= reach)
				take(cx, cy);
	// The stairs cells connected to them inside the footprint (and its
	// margin): 8-connected or within the gap, and a riser gap apart across
	// the risers.
	const int k = std::max(
	    1, static_cast<int>(
	           std::floor(m_options.stairsCellGap / g.resolution + 1e-6)));
	const int riserSteps =
	    axisKnown ? static_cast<int>(std::floor(
	                    m_options.stairsRiserGap / g.resolution + 1e-6))
	              : 0;
	const int minRowCells = static_cast<int>(
	    std::ceil(m_options.stairsRiserMinRow / g.resolution - 1e-6));
	const auto flight = [&](int cx, int cy)
	{ return inFootprint(cx, cy) && stairs(cx, cy); };
	for (std::size_t i = 0; i < queue.size(); i++)
	{
		const auto [cx0, cy0] = queue[i];
		for (int dy = -k; dy <= k; dy++)
			for (int dx = -k; dx <= k; dx++)
			{
				const int cx = cx0 + dx, cy = cy0 + dy;
				if (inFootprint(cx, cy)) take(cx, cy);
			}
		for (int s = 2; s <= riserSteps; s++)
			for (const int sign : {-1, 1})
			{
				const int cx =
				    cx0 + static_cast<int>(std::lround(sign * s * ax));
				const int cy =
				    cy0 + static_cast<int>(std::lround(sign * s * ay));
				if (inFootprint(cx, cy) &&
				    rowLength(cx, cy, ax, ay, flight) >= minRowCells)
					take(cx, cy);
			}
	}
	// A few cells are no flight (a stray labelled pixel): keep the mean.
	constexpr std::size_t kMinCells = 20;
	if (queue.size() < kMinCells) return;
	const auto [mx, my] = middleOfCells(queue, g);
	o.centroid.x = mx;
	o.centroid.y = my;
}

}  // namespace semnav
