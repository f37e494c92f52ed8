/* semnav: semantic navigation from tilting-laser sweeps */
#include "FieldRepair.h"

#include <algorithm>
#include <cmath>

namespace semnav::detail
{
FieldRepairer::FieldRepairer(
    const TraversabilityGrid& newU, const GoalLayer& newGoals,
    const CellIndex* start)
    : m_focused(start != nullptr),
      m_start(start ? *start : CellIndex{0, 0}),
      m_newU(newU.values()),
      m_newGoals(newGoals),
      m_g(newU.geometry()),
      m_L(newU.L()),
      m_a(newU.geometry().resolution),
      m_maxMagnitude(bucketWidth(m_g.resolution) / 16 * 0x1p52),
      m_examine(m_L, bucketWidth(m_g.resolution)),
      m_raise(m_L, bucketWidth(m_g.resolution))
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

void FieldRepairer::collectChanges(
    const CellRect& rect, const TraversabilityGrid& oldU,
    const GoalLayer& oldGoals)
{
	const CellRect r = rect.clipped(m_g);
	if (r.empty()) return;
	const double* uo = oldU.values().data();
	const double* un = m_newU.data();
	const std::int32_t* go = oldGoals.ids().data();
	const std::int32_t* gn = m_newGoals.ids().data();
	const bool sameGoals = &oldGoals == &m_newGoals;
	for (int row = r.row0; row < r.row1; row++)
		for (std::size_t i = m_g.index(row, r.col0),
		                 e = m_g.index(row, r.col1 - 1) + 1;
		     i < e; i++)
		{
			if (uo[i] == un[i] && (sameGoals || go[i] == gn[i])) continue;
			const bool bo = uo[i] >= m_L, bn = un[i] >= m_L;
			const bool so = go[i] != 0 && !bo, sn = sourceNew(i);
			if (go[i] != 0 && gn[i] == 0) m_removedGoals++;
			if (so && !sn) m_lostSources++;
			if (bo != bn || (!bo && uo[i] != un[i]) || so != sn)
			{
				m_changed.push_back({i, uo[i], so});
				m_changedBox.add(row, static_cast<int>(i - m_g.index(row, 0)));
			}
		}
	// Old u near the changes: all the repair reads of the old inputs.
	m_nearBox = m_changedBox.dilated(1).clipped(m_g);
	m_oldNear.clear();
	for (int row = m_nearBox.row0; row < m_nearBox.row1; row++)
		m_oldNear.insert(
		    m_oldNear.end(), uo + m_g.index(row, m_nearBox.col0),
		    uo + m_g.index(row, m_nearBox.col1 - 1) + 1);
}

bool FieldRepairer::nearChange(std::size_t i) const
{
	const auto r = static_cast<int>(i / static_cast<std::size_t>(m_g.cols));
	const auto c = static_cast<int>(i - m_g.index(r, 0));
	return m_nearBox.contains(r, c);
}

double FieldRepairer::oldUNear(std::size_t i) const
{
	const auto r = static_cast<int>(i / static_cast<std::size_t>(m_g.cols));
	const auto c = static_cast<int>(i - m_g.index(r, 0));
	const auto w = static_cast<std::size_t>(m_nearBox.col1 - m_nearBox.col0);
	return m_oldNear
	    [static_cast<std::size_t>(r - m_nearBox.row0) * w +
	     static_cast<std::size_t>(c - m_nearBox.col0)];
}

void FieldRepairer::pushDependants(std::size_t i, double v, double u)
{
	forNeighbours(
	    i,
	    [&](std::size_t j, int k)
	    {
		    if (m_x[j] > -kInf && m_x[j] == v - (m_a[k] + u))
			    m_examine.push(m_x[j], j, priority(m_x[j], j));
	    });
}

void FieldRepairer::examine(std::size_t i, double v)
{
	// Away from the changes u and the goals are unchanged, and a goal
	// cell holds L: the old u is read only near them.
	const bool near = nearChange(i);
	if ((near || v == m_L) && sourceNew(i)) return;
	// One pass: a neighbour still offering v keeps it; otherwise the
	// neighbours whose value came through i are examined in turn.
	const double uOld = near ? oldUNear(i) : m_newU[i];
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
	m_invalidated++;
	for (int k = 0; k < n; k++)
	{
		const std::size_t j = dependants[k];
		m_examine.push(m_x[j], j, priority(m_x[j], j));
	}
	deferRaise(i, m_examine.key(priority(v, i)));
}

void FieldRepairer::raiseFromNeighbours(std::size_t i, std::int64_t level)
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
	if (!(v > m_x[i])) return;
	// Offers from a level above `level` come from settled cells; a lower
	// one may come from a stale value: taken at its own level.
	const double p = priority(v, i);
	if (m_raise.key(p) > level)
	{
		m_raise.push(v, i | kDeferred, p);
		return;
	}
	m_x[i] = v;
	m_raised++;
	m_raise.push(v, i, p);
}

void FieldRepairer::deferRaise(std::size_t i, std::int64_t level)
{
	if (m_examineFirst)
		m_afterExamining.push_back(i);
	else
		raiseFromNeighbours(i, level);
}

void FieldRepairer::propagate(std::size_t i, double v)
{
	const double u = m_newU[i];
	forNeighbours(
	    i,
	    [&](std::size_t j, int k)
	    {
		    if (blockedNew(j)) return;
		    const double t = v - (m_a[k] + u);
		    if (t > m_x[j])
		    {
			    m_x[j] = t;
			    m_raised++;
			    m_raise.push(t, j, priority(t, j));
		    }
	    });
}

void FieldRepairer::seed(std::vector<double>& x)
{
	m_x = x.data();
	m_examineFirst = !m_focused;
	for (const Change& ch : m_changed)
	{
		const std::size_t c = ch.cell;
		const double v = m_x[c];
		if (v == -kInf) continue;  // nothing came through c
		if (blockedNew(c))
		{
			m_x[c] = -kInf;
			m_invalidated++;
			pushDependants(c, v, ch.oldU);
			continue;
		}
		if (m_newU[c] > ch.oldU) pushDependants(c, v, ch.oldU);
		if (ch.oldSource && !sourceNew(c)) m_examine.push(v, c, priority(v, c));
	}
	// Nothing is settled yet: every raise waits for its level (or, not
	// focused, for the examinations).
	for (const Change& ch : m_changed)
	{
		const std::size_t c = ch.cell;
		deferRaise(c, -1);
		// A cheaper (or newly free) cell offers more to its neighbours.
		if (!blockedNew(c) && (ch.oldU >= m_L || m_newU[c] < ch.oldU))
			forNeighbours(c, [&](std::size_t j, int) { deferRaise(j, -1); });
	}
}

double FieldRepairer::focus(std::size_t i) const
{
	const CellIndex c = m_g.cellAt(i);
	const int dr = std::abs(c.row - m_start.row);
	const int dc = std::abs(c.col - m_start.col);
	const int d = std::min(dr, dc), s = std::max(dr, dc) - d;
	return kFocusWeight * (d * m_a.diagonal + s * m_a.straight);
}

bool FieldRepairer::settles(std::int64_t level) const
{
	// Levels below `level` are done: a cell whose cost to go plus focus
	// lies in them is exact, the start's focus is 0.
	const double xs = m_x[m_g.index(m_start)];
	return xs > -kInf && m_raise.key(xs) < level;
}

double FieldRepairer::settledCost() const
{
	if (done()) return kInf;
	return static_cast<double>(m_settledLevel) * bucketWidth(m_g.resolution);
}

const char* FieldRepairer::run(
    std::vector<double>& x, std::size_t workLimit, bool bounded,
    FieldRepairStats& stats)
{
	m_x = x.data();
	m_examineFirst = !bounded;
	const char* stopped = nullptr;
	for (;;)
	{
		std::int64_t le = INT64_MAX, lr = INT64_MAX;
		const bool he = m_examine.peek(le);
		if (!he && !m_afterExamining.empty())
		{
			// Every value is settled: the raises are taken at once.
			for (const std::size_t i : m_afterExamining)
				raiseFromNeighbours(i, INT64_MAX);
			m_afterExamining.clear();
		}
		const bool hr = m_raise.peek(lr);
		if (!he && !hr) break;
		const std::int64_t level = std::min(le, lr);
		m_settledLevel = level;
		if (bounded && settles(level)) break;
		BucketQueue::Entry e;
		// A level's examinations first: its raises read settled values.
		// Unbounded, every examination first (the raises of the cells
		// they invalidate wait until then).
		const bool examining = he && (le <= lr || !bounded);
		(examining ? m_examine : m_raise).pop(e);
		// The work limit counts examinations and propagations.
		if (!(e.cell & kDeferred) && ++m_work > workLimit)
		{
			stopped = kWorkLimitReached;
			break;
		}
		if (e.value < -m_maxMagnitude)
		{
			stopped = kValueTooLarge;
			break;
		}
		const std::size_t i = e.cell & ~kDeferred;
		if (examining)
		{
			if (m_x[i] == e.value) examine(i, e.value);
		}
		else if (e.cell & kDeferred)
			raiseFromNeighbours(i, level);
		else if (m_x[i] == e.value)
			propagate(i, e.value);
	}
	// Counts since the last run (the seed's with the first).
	stats.invalidatedCells += m_invalidated - m_reported[0];
	stats.raisedCells += m_raised - m_reported[1];
	stats.poppedCells += m_work - m_reported[2];
	m_reported[0] = m_invalidated;
	m_reported[1] = m_raised;
	m_reported[2] = m_work;
	return stopped;
}

}  // namespace semnav::detail
