/* semnav: semantic navigation from tilting-laser sweeps */
#include "FieldRepair.h"

#include <cmath>
#include <cstdint>

namespace semnav::detail
{
FieldRepairer::FieldRepairer(
    std::vector<double>& x, const TraversabilityGrid& oldU,
    const GoalLayer& oldGoals, const TraversabilityGrid& newU,
    const GoalLayer& newGoals)
    : m_x(x),
      m_oldU(oldU.values()),
      m_newU(newU.values()),
      m_oldGoals(oldGoals),
      m_newGoals(newGoals),
      m_g(newU.geometry()),
      m_L(newU.L()),
      m_a(newU.geometry().resolution),
      m_maxMagnitude(bucketWidth(m_g.resolution) / 16 * 0x1p52),
      m_queue(m_L, bucketWidth(newU.geometry().resolution))
{
	for (int k = 0; k < 8; k++)
		m_offset[k] = static_cast<std::ptrdiff_t>(kDr[k]) * m_g.cols + kDc[k];
}

bool FieldRepairer::applicable(const GridGeometry& g, double L)
{
	const double ulp = std::nextafter(L, 2 * L) - L;
	return 16 * ulp <= bucketWidth(g.resolution) && g.cellCount() <= UINT32_MAX;
}

template <class F>
void FieldRepairer::forNeighbours(std::size_t i, const F& f) const
{
	const auto i32 = static_cast<std::uint32_t>(i);
	const auto cols = static_cast<std::uint32_t>(m_g.cols);
	const int r = static_cast<int>(i32 / cols);
	const int c = static_cast<int>(i32 - static_cast<std::uint32_t>(r) * cols);
	if (r > 0 && c > 0 && r + 1 < m_g.rows && c + 1 < m_g.cols)
	{
		for (int k = 0; k < 8; k++)
			f(static_cast<std::size_t>(
			      static_cast<std::ptrdiff_t>(i) + m_offset[k]),
			  k);
		return;
	}
	for (int k = 0; k < 8; k++)
	{
		const int rr = r + kDr[k], cc = c + kDc[k];
		if (m_g.contains(rr, cc)) f(m_g.index(rr, cc), k);
	}
}

void FieldRepairer::collectChanges(const CellRect& rect)
{
	const CellRect r = rect.clipped(m_g);
	if (r.empty()) return;
	const double* uo = m_oldU.data();
	const double* un = m_newU.data();
	const std::int32_t* go = m_oldGoals.ids().data();
	const std::int32_t* gn = m_newGoals.ids().data();
	const bool sameGoals = &m_oldGoals == &m_newGoals;
	for (int row = r.row0; row < r.row1; row++)
		for (std::size_t i = m_g.index(row, r.col0),
		                 e = m_g.index(row, r.col1 - 1) + 1;
		     i < e; i++)
		{
			if (uo[i] == un[i] && (sameGoals || go[i] == gn[i])) continue;
			const bool bo = uo[i] >= m_L, bn = un[i] >= m_L;
			const bool so = sourceOld(i), sn = sourceNew(i);
			if (go[i] != 0 && gn[i] == 0) m_removedGoals++;
			if (so && !sn) m_lostSources++;
			if (bo != bn || (!bo && uo[i] != un[i]) || so != sn)
			{
				m_changed.push_back(i);
				m_changedBox.add(row, static_cast<int>(i - m_g.index(row, 0)));
			}
		}
}

void FieldRepairer::pushDependants(std::size_t i, double v, double u)
{
	forNeighbours(
	    i,
	    [&](std::size_t j, int k)
	    {
		    if (m_x[j] > -kInf && m_x[j] == v - (m_a[k] + u))
			    m_queue.push(m_x[j], j);
	    });
}

void FieldRepairer::invalidateCell(std::size_t i, double v, double u)
{
	m_x[i] = -kInf;
	m_invalidated.push_back(i);
	pushDependants(i, v, u);
}

bool FieldRepairer::nearChange(std::size_t i) const
{
	const auto r = static_cast<int>(i / static_cast<std::size_t>(m_g.cols));
	const auto c = static_cast<int>(i - m_g.index(r, 0));
	return r >= m_changedBox.row0 - 1 && r <= m_changedBox.row1 &&
	       c >= m_changedBox.col0 - 1 && c <= m_changedBox.col1;
}

void FieldRepairer::examine(std::size_t i, double v)
{
	// Away from the changes u and the goals are unchanged, and a goal
	// cell holds L: the cold arrays (old u, goal ids) are read only near.
	const bool near = nearChange(i);
	if ((near || v == m_L) && sourceNew(i)) return;
	// One pass: a neighbour still offering v keeps it; otherwise the
	// neighbours whose value came through i are examined in turn.
	const double uOld = near ? m_oldU[i] : m_newU[i];
	std::size_t dependants[8];
	int n = 0;
	bool supported = false;
	forNeighbours(
	    i,
	    [&](std::size_t j, int k)
	    {
		    if (supported) return;
		    const double xj = m_x[j];
		    if (!blockedNew(j) && xj - (m_a[k] + m_newU[j]) >= v)
			    supported = true;
		    else if (xj > -kInf && xj == v - (m_a[k] + uOld))
			    dependants[n++] = j;
	    });
	if (supported) return;
	m_x[i] = -kInf;
	m_invalidated.push_back(i);
	for (int k = 0; k < n; k++) m_queue.push(m_x[dependants[k]], dependants[k]);
}

const char* FieldRepairer::invalidate(std::size_t workLimit)
{
	for (const std::size_t c : m_changed)
	{
		const double v = m_x[c];
		if (v == -kInf) continue;  // nothing came through c
		if (blockedNew(c))
		{
			invalidateCell(c, v, m_oldU[c]);
			continue;
		}
		if (m_newU[c] > m_oldU[c]) pushDependants(c, v, m_oldU[c]);
		if (sourceOld(c) && !sourceNew(c)) m_queue.push(v, c);
	}
	// Highest old value first: a cell's supports (higher values) are final
	// when it is examined.
	BucketQueue::Entry e;
	while (m_queue.pop(e))
	{
		if (++m_work > workLimit) return kWorkLimitReached;
		if (e.value < -m_maxMagnitude) return kValueTooLarge;
		if (m_x[e.cell] == e.value) examine(e.cell, e.value);
	}
	return nullptr;
}

void FieldRepairer::raiseFromNeighbours(std::size_t i)
{
	if (blockedNew(i)) return;
	// Away from the changes a goal cell already holds L.
	double v = nearChange(i) && sourceNew(i) ? m_L : -kInf;
	forNeighbours(
	    i,
	    [&](std::size_t j, int k)
	    {
		    if (blockedNew(j)) return;
		    const double t = m_x[j] - (m_a[k] + m_newU[j]);
		    if (t > v) v = t;
	    });
	if (v > m_x[i])
	{
		m_x[i] = v;
		m_raised++;
		m_queue.push(v, i);
	}
}

const char* FieldRepairer::propagate(std::size_t workLimit)
{
	m_queue = BucketQueue(m_L, bucketWidth(m_g.resolution));
	for (const std::size_t i : m_invalidated) raiseFromNeighbours(i);
	for (const std::size_t c : m_changed)
	{
		raiseFromNeighbours(c);
		// A cheaper (or newly free) cell offers more to its neighbours.
		if (!blockedNew(c) && (m_oldU[c] >= m_L || m_newU[c] < m_oldU[c]))
			forNeighbours(
			    c, [&](std::size_t j, int) { raiseFromNeighbours(j); });
	}
	// Highest value first: each cell leaves the queue once at its final
	// value (stale entries are skipped); the order only saves work here.
	BucketQueue::Entry e;
	while (m_queue.pop(e))
	{
		if (++m_work > workLimit) return kWorkLimitReached;
		if (m_x[e.cell] != e.value) continue;
		const double u = m_newU[e.cell];
		forNeighbours(
		    e.cell,
		    [&](std::size_t j, int k)
		    {
			    if (blockedNew(j)) return;
			    const double t = e.value - (m_a[k] + u);
			    if (t > m_x[j])
			    {
				    m_x[j] = t;
				    m_raised++;
				    m_queue.push(t, j);
			    }
		    });
	}
	return nullptr;
}

const char* FieldRepairer::run(std::size_t workLimit, FieldRepairStats& stats)
{
	stats.changedCells = m_changed.size();
	const char* stopped = invalidate(workLimit);
	if (!stopped) stopped = propagate(workLimit);
	stats.invalidatedCells = m_invalidated.size();
	stats.raisedCells = m_raised;
	stats.poppedCells = m_work;
	return stopped;
}

}  // namespace semnav::detail
