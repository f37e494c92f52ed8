/* semnav: semantic navigation from tilting-laser sweeps */
#include "DiffusionKernels.h"

#include <algorithm>
#include <limits>
#include <thread>

namespace semnav::detail
{
std::vector<double> effectiveU(const TraversabilityGrid& u)
{
	std::vector<double> ue(u.values());
	const double L = u.L();
	for (double& v : ue)
		if (v >= L) v = kInf;
	return ue;
}

std::size_t initialField(
    const TraversabilityGrid& u, const GoalLayer& goals, std::vector<double>& x)
{
	x.assign(u.values().size(), -kInf);
	std::size_t n = 0;
	for (std::size_t i = 0; i < x.size(); i++)
		if (goals.isGoal(i) && !u.blocked(i))
		{
			x[i] = u.L();
			n++;
		}
	return n;
}

namespace
{
/** Column range [lo, hi); empty when lo >= hi. */
struct Range
{
	int lo = std::numeric_limits<int>::max();
	int hi = std::numeric_limits<int>::min();
	bool empty() const { return lo >= hi; }
	void add(int a, int b)
	{
		lo = std::min(lo, a);
		hi = std::max(hi, b);
	}
	void add(const Range& r)
	{
		if (!r.empty()) add(r.lo, r.hi);
	}
	void clear() { *this = Range(); }
};

struct Scratch
{
	std::vector<double> tS, tD, cand;
	explicit Scratch(int cols) : tS(cols), tD(cols + 2), cand(cols) {}
};

/** Relaxes row i: first from the source row xs (the row above in a down
 * pass, below in an up pass) where it changed (`src`), then along the row
 * from the cells that changed or are marked `self`, both ways, as long as
 * values rise. Blocked cells (ue = inf) stay at -inf. Returns the columns
 * whose value rose. */
Range relaxRow(
    double* xi, const double* ui, const double* xs, const double* us,
    const Range& src, const Range& self, int cols, const Steps& a, Scratch& s)
{
	Range ch;
	if (xs && !src.empty())
	{
		// Targets [b, e) can see a changed source column.
		const int b = std::max(0, src.lo - 1), e = std::min(cols, src.hi + 1);
		const int sb = std::max(0, b - 1), se = std::min(cols, e + 1);
		double* tS = s.tS.data();
		double* tD = s.tD.data();  // tD[j + 1]: diagonal term of column j
		tD[sb] = tD[se + 1] = -kInf;
		for (int j = sb; j < se; j++)
		{
			tS[j] = xs[j] - (a.straight + us[j]);
			tD[j + 1] = xs[j] - (a.diagonal + us[j]);
		}
		// Candidates first, then only the span where one is higher.
		double* cand = s.cand.data();
		for (int j = b; j < e; j++)
		{
			double v = tS[j];
			v = tD[j] > v ? tD[j] : v;
			v = tD[j + 2] > v ? tD[j + 2] : v;
			cand[j] = ui[j] == kInf ? -kInf : v;
		}
		int j0 = b;
		while (j0 < e && !(cand[j0] > xi[j0])) j0++;
		if (j0 < e)
		{
			int j1 = e;
			while (!(cand[j1 - 1] > xi[j1 - 1])) j1--;
			for (int j = j0; j < j1; j++)
				xi[j] = cand[j] > xi[j] ? cand[j] : xi[j];
			ch.add(j0, j1);
		}
	}
	Range h = ch;
	h.add(self);
	if (h.empty()) return ch;
	// Left to right: every column of h, then on while values keep rising.
	int last = -1;
	for (int j = h.lo + 1; j < cols && (j <= h.hi || last == j - 1); j++)
	{
		const double t = xi[j - 1] - (a.straight + ui[j - 1]);
		if (t > xi[j] && ui[j] != kInf)
		{
			xi[j] = t;
			ch.add(j, j + 1);
			last = j;
		}
	}
	// Right to left from the cells of h (cells raised by the left-to-right
	// scan cannot raise their left neighbours: step costs are positive).
	last = cols;
	for (int j = h.hi - 2; j >= 0 && (j >= h.lo - 1 || last == j + 1); j--)
	{
		const double t = xi[j + 1] - (a.straight + ui[j + 1]);
		if (t > xi[j] && ui[j] != kInf)
		{
			xi[j] = t;
			ch.add(j, j + 1);
			last = j;
		}
	}
	return ch;
}

/** Rows [r0, r1) relaxed by one thread. Rows r0 - 1 and r1 belong to the
 * neighbour bands: they are read from snapshots ("ghosts") refreshed between
 * passes. Dirty ranges hold the columns whose constraints toward a
 * neighbour row are not verified yet (changes not yet seen by it). */
struct Band
{
	int r0 = 0, r1 = 0;
	std::vector<Range> dirtyBelow, dirtyAbove, self;
	std::vector<double> ghostTop, ghostBottom;
	Range ghostTopDirty, ghostBottomDirty;
	long rowUpdates = 0;
	Scratch scratch;
	Band(int a, int b, int cols) : r0(a), r1(b), scratch(cols) {}
};

/** Copies `row` into `ghost` and returns the columns that differed. */
Range snapshot(const double* row, std::vector<double>& ghost)
{
	Range r;
	const int n = static_cast<int>(ghost.size());
	int j0 = 0;
	while (j0 < n && ghost[j0] == row[j0]) j0++;
	if (j0 == n) return r;
	int j1 = n;
	while (ghost[j1 - 1] == row[j1 - 1]) j1--;
	std::copy(row + j0, row + j1, ghost.begin() + j0);
	r.add(j0, j1);
	return r;
}

/** Runs f(0..n-1), f(0) on the calling thread. */
template <class F>
void runParallel(int n, const F& f)
{
	std::vector<std::thread> pool;
	for (int k = 1; k < n; k++) pool.emplace_back(f, k);
	f(0);
	for (auto& t : pool) t.join();
}
}  // namespace

int diffuseSweep(
    const GridGeometry& g, const std::vector<double>& ue,
    std::vector<double>& x, int maxIterations, int threads, long& rowUpdates)
{
	const int rows = g.rows, cols = g.cols;
	const Steps a(g.resolution);
	const int nBands = std::max(1, std::min(threads, rows / 16));
	std::vector<Band> bands;
	for (int b = 0; b < nBands; b++)
	{
		const int r0 = static_cast<int>(static_cast<long>(rows) * b / nBands);
		const int r1 =
		    static_cast<int>(static_cast<long>(rows) * (b + 1) / nBands);
		Band B(r0, r1, cols);
		// Everything is unverified at the start.
		Range all;
		all.add(0, cols);
		B.dirtyBelow.assign(r1 - r0, all);
		B.dirtyAbove.assign(r1 - r0, all);
		B.self.assign(r1 - r0, all);
		if (r0 > 0)
		{
			B.ghostTop.assign(
			    x.begin() + g.index(r0 - 1, 0), x.begin() + g.index(r0, 0));
			B.ghostTopDirty = all;
		}
		if (r1 < rows)
		{
			B.ghostBottom.assign(
			    x.begin() + g.index(r1, 0), x.begin() + g.index(r1 + 1, 0));
			B.ghostBottomDirty = all;
		}
		bands.push_back(std::move(B));
	}

	double* X = x.data();
	const double* U = ue.data();
	const auto pass = [&](Band& B, bool down)
	{
		const int n = B.r1 - B.r0;
		for (int k = 0; k < n; k++)
		{
			const int li = down ? k : n - 1 - k;
			const int i = B.r0 + li;
			const int src = down ? i - 1 : i + 1;
			const double* xs = nullptr;
			Range* dirty = nullptr;
			if (src >= 0 && src < rows)
			{
				if (src < B.r0)
				{
					xs = B.ghostTop.data();
					dirty = &B.ghostTopDirty;
				}
				else if (src >= B.r1)
				{
					xs = B.ghostBottom.data();
					dirty = &B.ghostBottomDirty;
				}
				else
				{
					xs = X + g.index(src, 0);
					dirty = down ? &B.dirtyBelow[src - B.r0]
					             : &B.dirtyAbove[src - B.r0];
				}
			}
			const Range srcRange = dirty ? *dirty : Range();
			if (srcRange.empty() && B.self[li].empty()) continue;
			if (dirty) dirty->clear();
			const Range self = B.self[li];
			B.self[li].clear();
			B.rowUpdates++;
			const Range ch = relaxRow(
			    X + g.index(i, 0), U + g.index(i, 0), xs,
			    xs ? U + g.index(src, 0) : nullptr, srcRange, self, cols, a,
			    B.scratch);
			B.dirtyBelow[li].add(ch);
			B.dirtyAbove[li].add(ch);
		}
	};

	bool down = true;
	for (int passes = 0;; down = !down)
	{
		// Refresh the ghosts; the edge rows' own dirty ranges are replaced by
		// the ghost differences (or have no neighbour at the grid border).
		bool pending = false;
		for (Band& B : bands)
		{
			if (!B.ghostTop.empty())
				B.ghostTopDirty.add(
				    snapshot(X + g.index(B.r0 - 1, 0), B.ghostTop));
			if (!B.ghostBottom.empty())
				B.ghostBottomDirty.add(
				    snapshot(X + g.index(B.r1, 0), B.ghostBottom));
			B.dirtyAbove.front().clear();
			B.dirtyBelow.back().clear();
		}
		for (const Band& B : bands)
		{
			pending = pending || !B.ghostTopDirty.empty() ||
			          !B.ghostBottomDirty.empty();
			for (std::size_t k = 0; k < B.self.size() && !pending; k++)
				pending = !B.self[k].empty() || !B.dirtyBelow[k].empty() ||
				          !B.dirtyAbove[k].empty();
		}
		// Converged (eq. (11)): no constraint left unverified.
		if (!pending)
		{
			rowUpdates = 0;
			for (const Band& B : bands) rowUpdates += B.rowUpdates;
			return passes;
		}
		if (maxIterations > 0 && passes >= maxIterations) return -1;
		runParallel(nBands, [&](int b) { pass(bands[b], down); });
		passes++;
	}
}

int diffuseJacobi(
    const GridGeometry& g, const std::vector<double>& ue,
    std::vector<double>& x, int maxIterations, int threads)
{
	const Steps a(g.resolution);
	const std::vector<double> source(x);  // g - u of eq. (10)
	std::vector<double> next(x.size());
	const int rows = g.rows, cols = g.cols;
	const int nThreads = std::max(1, std::min(threads, rows));
	std::vector<char> changed(nThreads);
	const auto update = [&](int t)
	{
		changed[t] = 0;
		const int r0 = static_cast<int>(static_cast<long>(rows) * t / nThreads);
		const int r1 =
		    static_cast<int>(static_cast<long>(rows) * (t + 1) / nThreads);
		for (int r = r0; r < r1; r++)
			for (int c = 0; c < cols; c++)
			{
				const std::size_t i = g.index(r, c);
				if (ue[i] == kInf)
				{
					next[i] = -kInf;
					continue;
				}
				double m = source[i];
				for (int k = 0; k < 8; k++)
				{
					const int rr = r + kDr[k], cc = c + kDc[k];
					if (!g.contains(rr, cc)) continue;
					const std::size_t j = g.index(rr, cc);
					const double v = x[j] - (a[k] + ue[j]);
					if (v > m) m = v;
				}
				next[i] = m;
				if (m != x[i]) changed[t] = 1;
			}
	};
	for (int it = 0;;)
	{
		if (maxIterations > 0 && it >= maxIterations) return -1;
		runParallel(nThreads, update);
		x.swap(next);
		it++;
		if (std::none_of(
		        changed.begin(), changed.end(), [](char c) { return c; }))
			return it;
	}
}

}  // namespace semnav::detail
