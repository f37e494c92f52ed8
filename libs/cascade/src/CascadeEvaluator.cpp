/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/cascade/CascadeError.h>
#include <semnav/cascade/CascadeEvaluator.h>

#include <algorithm>
#include <cstddef>
#include <cstring>

#include "CompiledFeature.h"
#include "StumpBatch.h"

namespace semnav
{
// evaluateStages indexes the leaves as an array.
static_assert(
    offsetof(HaarCascade::Stump, right) ==
    offsetof(HaarCascade::Stump, left) + sizeof(float));

CascadeEvaluator::CascadeEvaluator(HaarCascade cascade)
    : m_cascade(std::move(cascade))
{
	m_cascade.validate();
}

CascadeEvaluator::~CascadeEvaluator() = default;
CascadeEvaluator::CascadeEvaluator(CascadeEvaluator&& o) noexcept
{
	*this = std::move(o);
}
CascadeEvaluator& CascadeEvaluator::operator=(CascadeEvaluator&& o) noexcept
{
	m_cascade = std::move(o.m_cascade);
	m_compiled = std::move(o.m_compiled);
	m_flat = std::move(o.m_flat);
	m_stageBegin = std::move(o.m_stageBegin);
	m_maxOffset = o.m_maxOffset;
	m_simd = o.m_simd;
	m_stride = o.m_stride;
	m_own = std::move(o.m_own);
	m_ii = o.m_ii == &o.m_own ? &m_own : o.m_ii;
	return *this;
}

void CascadeEvaluator::setImage(const cv::Mat& image)
{
	m_own.compute(image, m_cascade.hasTiltedFeatures());
	m_ii = &m_own;
	compile();
}

void CascadeEvaluator::setIntegralImages(const IntegralImages& ii)
{
	if (m_cascade.hasTiltedFeatures() && !ii.hasTilted())
		throw CascadeError(
		    "CascadeEvaluator: the cascade has tilted features but the "
		    "integral images have no tilted part");
	m_ii = &ii;
	compile();
}

void CascadeEvaluator::compile()
{
	const int stride = static_cast<int>(m_ii->sum().step1());
	if (stride == m_stride) return;
	m_compiled.clear();
	m_compiled.reserve(m_cascade.features.size());
	for (const auto& f : m_cascade.features) m_compiled.emplace_back(f, stride);
	m_flat.clear();
	m_stageBegin.assign(1, 0);
	for (const auto& stage : m_cascade.stages)
	{
		for (const auto& st : stage.stumps)
		{
			const detail::CompiledFeature& f = m_compiled[st.featureIdx];
			detail::FlatStump fs;
			for (int i = 0; i < 3; i++)
			{
				for (int j = 0; j < 4; j++) fs.ofs[4 * i + j] = f.ofs[i][j];
				fs.weight[i] = f.weight[i];
			}
			fs.rects = f.weight[2] != 0.0f ? 3 : 2;
			fs.tilted = f.tilted;
			fs.threshold = st.threshold;
			fs.leaf[0] = st.left;
			fs.leaf[1] = st.right;
			m_flat.push_back(fs);
		}
		m_stageBegin.push_back(m_flat.size());
	}
	m_maxOffset = 0;
	for (const auto& fs : m_flat)
		for (int o : fs.ofs) m_maxOffset = std::max(m_maxOffset, o);
	m_stride = stride;
}

bool CascadeEvaluator::simdActive() const
{
	return m_simd && detail::cpuHasAvx2();
}

CascadeEvaluator::Result CascadeEvaluator::evaluate(cv::Point origin) const
{
	return evaluateStages(origin, 0, m_cascade.stages.size());
}

CascadeEvaluator::Result CascadeEvaluator::evaluateStages(
    cv::Point o, std::size_t first, std::size_t count) const
{
	Result res;
	const IntegralImages& ii = *m_ii;
	const cv::Size win = m_cascade.windowSize;
	const cv::Size img = ii.imageSize();
	// setWindow: pt.x + width >= szi.width (= image width + 1) is outside.
	if (o.x < 0 || o.y < 0 || o.x + win.width > img.width ||
	    o.y + win.height > img.height)
		return res;
	const int32_t* sum = ii.sum().ptr<int32_t>(o.y) + o.x;
	const double* sq = ii.sqsum().ptr<double>(o.y) + o.x;
	const int32_t* tilt =
	    ii.hasTilted() ? ii.tilted().ptr<int32_t>(o.y) + o.x : nullptr;
	float nf = 1.f;
	if (!detail::varianceNormFactor(
	        sum, sq, static_cast<int>(ii.sum().step1()),
	        static_cast<int>(ii.sqsum().step1()), win, nf))
		return res;
	const std::size_t end = std::min(first + count, m_cascade.stages.size());
	for (std::size_t s = first; s < end; s++)
	{
		const auto& stage = m_cascade.stages[s];
		double tmp = 0;
		for (const auto& st : stage.stumps)
		{
			// OpenCV: double value = optfeature.calc(pwin) * nf (float).
			const double value = m_compiled[st.featureIdx].calc(sum, tilt) * nf;
			// Branch-free leaf (left, right adjacent): the comparison is
			// unpredictable, a mispredicted jump cost more than the stump.
			const float* leaves = &st.left;
			tmp += leaves[!(value < st.threshold)];
		}
		res.sum = tmp;
		if (tmp < stage.threshold - detail::kStageThresholdEps)
		{
			res.stage = static_cast<int>(s);
			return res;
		}
	}
	res.stage = static_cast<int>(end);
	return res;
}

std::vector<CascadeEvaluator::ScannedWindow> CascadeEvaluator::scanScaleOne()
    const
{
	std::vector<ScannedWindow> out;
	const cv::Size img = m_ii->imageSize();
	const cv::Size win = m_cascade.windowSize;
	// Working size: szi - window = image + 1 - window.
	const int nx = img.width + 1 - win.width, ny = img.height + 1 - win.height;
	const int step = 2;  // ScaleData::ystep for scale < 2
	for (int y = 0; y < ny; y += step)
		for (int x = 0; x < nx; x += step)
		{
			const Result r = evaluate({x, y});
			out.push_back({{x, y}, r});
			if (r.stage == 0) x += step;  // OpenCV: if (result == 0) x += yStep
		}
	return out;
}

void CascadeEvaluator::scanWindows(
    const std::vector<cv::Point>& windows, int step,
    std::vector<Result>& results)
{
	results.assign(windows.size(), Result());
	if (windows.empty()) return;
	const int grid = placeOnGrid(windows, step);
	markVarianceWindows(windows, grid);
	// The positions still in, in grid order, with their segments.
	Live* live = m_live.data();
	const int32_t* windowOf = m_gridWindow.data();
	std::size_t nLive = 0;
	for (std::size_t si = 0; si < m_segments.size(); si++)
		for (int j = 0; j < m_segments[si].count; j++)
			if (m_alive[m_segments[si].grid + j])
				live[nLive++] = {m_segments[si].grid + j, static_cast<int>(si)};
	const std::size_t nStages = m_cascade.stages.size();
	if (nStages == 0)
	{
		for (std::size_t k = 0; k < nLive; k++)
			results[windowOf[live[k].grid]].stage = 0;
		return;
	}
	// Stage 0 on every window, then OpenCV's skip in visiting order: the
	// window after a stage-0 rejection is not visited (its stage-0 sum is
	// dropped).
	runStage(0, step, nLive);
	nLive = applyFirstStage(windows, step, results, nLive);
	const double* sums = m_gridSums.data();
	Result* res = results.data();
	for (std::size_t s = 1; s < nStages && nLive > 0; s++)
	{
		runStage(s, step, nLive);
		const float thr =
		    m_cascade.stages[s].threshold - detail::kStageThresholdEps;
		// Without branches (a stage passes 60-70 % of the windows: the
		// branch is unpredictable): every window gets this stage's result,
		// which the stage that rejects it or the end overwrites.
		std::size_t kept = 0;
		for (std::size_t k = 0; k < nLive; k++)
		{
			const Live l = live[k];
			const double sum = sums[l.grid];
			Result& r = res[windowOf[l.grid]];
			r.sum = sum;
			r.stage = static_cast<int>(s);
			live[kept] = l;
			kept += !(sum < thr);
		}
		nLive = kept;
	}
	for (std::size_t k = 0; k < nLive; k++)
	{
		Result& r = res[windowOf[live[k].grid]];
		r.sum = sums[live[k].grid];
		r.stage = static_cast<int>(nStages);
	}
}

int CascadeEvaluator::placeOnGrid(
    const std::vector<cv::Point>& windows, int step)
{
	const cv::Size win = m_cascade.windowSize;
	const cv::Size img = m_ii->imageSize();
	// Windows on a grid: runs of one row, `step` apart (the windows of a
	// detectMultiScale level), each a segment of grid positions; positions
	// between the windows of a run are not windows (never alive).
	std::vector<Segment>& segs = m_segments;
	segs.clear();
	m_gridOf.resize(windows.size());
	int grid = 0;
	const auto inside = [&](cv::Point o)
	{
		return o.x >= 0 && o.y >= 0 && o.x + win.width <= img.width &&
		       o.y + win.height <= img.height;
	};
	for (std::size_t i = 0; i < windows.size(); i++)
	{
		const cv::Point o = windows[i];
		// Windows outside the image (stage -1) stay off the grid, so every
		// position of a segment lies inside the image.
		if (!inside(o))
		{
			m_gridOf[i] = -1;
			continue;
		}
		if (!segs.empty())
		{
			Segment& sg = segs.back();
			const int dx = o.x - sg.x0;
			const int j = step > 0 ? dx / step : 0;
			// Same row, on the grid, further right, not too far (a long gap
			// would only add dead positions).
			if (o.y == sg.y && step > 0 && dx % step == 0 && j >= sg.count &&
			    j - sg.count < 64)
			{
				grid += j - sg.count;
				sg.count = j + 1;
				m_gridOf[i] = grid++;
				continue;
			}
		}
		segs.push_back({o.x, o.y, grid, 1});
		m_gridOf[i] = grid++;
	}
	return grid;
}

void CascadeEvaluator::markVarianceWindows(
    const std::vector<cv::Point>& windows, int grid)
{
	const IntegralImages& ii = *m_ii;
	const cv::Size win = m_cascade.windowSize;
	const int stride = static_cast<int>(ii.sum().step1());
	const int sqStride = static_cast<int>(ii.sqsum().step1());
	const int32_t* sum0 = ii.sum().ptr<int32_t>(0);
	const double* sq0 = ii.sqsum().ptr<double>(0);
	m_alive.assign(grid + 8, 0);
	m_gridNf.assign(grid + 8, 0.f);
	m_gridSums.assign(grid + 8, 0.0);
	m_gridWindow.assign(grid, -1);
	for (std::size_t i = 0; i < windows.size(); i++)
	{
		const cv::Point o = windows[i];
		const int g = m_gridOf[i];
		if (g < 0) continue;
		m_gridWindow[g] = static_cast<int32_t>(i);
		float nf = 1.f;
		if (!detail::varianceNormFactor(
		        sum0 + o.y * stride + o.x, sq0 + o.y * sqStride + o.x, stride,
		        sqStride, win, nf))
			continue;
		m_gridNf[g] = nf;
		m_alive[g] = 1;
	}
	m_live.resize(static_cast<std::size_t>(grid));
}

void CascadeEvaluator::runStage(std::size_t s, int step, std::size_t nLive)
{
	const IntegralImages& ii = *m_ii;
	const int stride = static_cast<int>(ii.sum().step1());
	const int32_t* sum0 = ii.sum().ptr<int32_t>(0);
	const int32_t* tilt0 =
	    ii.hasTilted() ? ii.tilted().ptr<int32_t>(0) : nullptr;
	// The last entry of the integral images a read may reach.
	const int64_t lastEntry =
	    int64_t(ii.sum().rows - 1) * stride + ii.sum().cols - 1;
	// Dense eight-window blocks (AVX2) cover eight neighbouring positions
	// of a segment of at least eight (every position lies between two
	// windows of the run, so inside the image), or a shorter segment and
	// the positions after it (dropped).
	const bool simd = simdActive() && (step == 1 || step == 2);
	// (Raw pointers: the compiler cannot keep vector data pointers in
	// registers across the stores.)
	const std::vector<Segment>& segs = m_segments;
	const Live* live = m_live.data();
	const float* nfs = m_gridNf.data();
	double* sums = m_gridSums.data();
	const detail::FlatStump* st = m_flat.data() + m_stageBegin[s];
	const std::size_t n = m_stageBegin[s + 1] - m_stageBegin[s];
	// Windows no block takes, four side by side (independent sums: a
	// window alone waits on each of its additions).
	int32_t pendBase[4];
	float pendNf[4];
	int pendGrid[4];
	int pending = 0;
	const auto flush = [&]()
	{
		if (pending >= 2)
		{
			for (int i = pending; i < 4; i++)
			{
				pendBase[i] = pendBase[0];
				pendNf[i] = pendNf[0];
			}
			double out[4];
			detail::stageSumsAt4(st, n, sum0, tilt0, pendBase, pendNf, out);
			for (int i = 0; i < pending; i++) sums[pendGrid[i]] = out[i];
		}
		else
			for (int i = 0; i < pending; i++)
				sums[pendGrid[i]] = detail::stageSum(
				    st, n, sum0, tilt0, pendBase[i], pendNf[i]);
		pending = 0;
	};
	for (std::size_t k = 0; k < nLive;)
	{
		const Segment& sg = segs[live[k].segment];
		const int32_t base = sg.y * stride + sg.x0;
		const int j = live[k].grid - sg.grid;
		if (simd)
		{
			// The block of j; with two or more positions in, all eight
			// at once. A segment shorter than eight is one block whose
			// lanes past its end are computed and dropped (their reads
			// stay within the integral images: checked below).
			const int jb =
			    sg.count >= 8 ? std::min(j / 8 * 8, sg.count - 8) : 0;
			const int g = sg.grid + jb;
			const int gEnd = std::min(g + 8, sg.grid + sg.count);
			std::size_t e = k + 1;
			while (e < nLive && live[e].grid < gEnd) e++;
			const int32_t b = base + step * jb;
			// The block's loads end (step 2: one entry) past the last
			// window's corners.
			if (e - k >= 2 && b + 8 * step - 1 + m_maxOffset <= lastEntry)
			{
				double block[8];
				detail::stageSums8(st, n, sum0, tilt0, b, step, nfs + g, block);
				for (; k < e; k++) sums[live[k].grid] = block[live[k].grid - g];
				continue;
			}
		}
		pendBase[pending] = base + step * j;
		pendNf[pending] = nfs[live[k].grid];
		pendGrid[pending] = live[k].grid;
		if (++pending == 4) flush();
		k++;
	}
	flush();
}

std::size_t CascadeEvaluator::applyFirstStage(
    const std::vector<cv::Point>& windows, int step,
    std::vector<Result>& results, std::size_t nLive)
{
	uint8_t* alive = m_alive.data();
	const double* sums = m_gridSums.data();
	Live* live = m_live.data();
	const float thr0 =
	    m_cascade.stages[0].threshold - detail::kStageThresholdEps;
	cv::Point skip(-1, -1);
	const int* gridOf = m_gridOf.data();
	for (std::size_t i = 0; i < windows.size(); i++)
	{
		const int g = gridOf[i];
		if (windows[i] == skip)
		{
			results[i].stage = kNotVisited;
			if (g >= 0) alive[g] = 0;
			continue;
		}
		if (g < 0 || !alive[g]) continue;  // outside, variance: -1
		results[i].sum = sums[g];
		if (sums[g] < thr0)
		{
			results[i].stage = 0;
			alive[g] = 0;
			skip = cv::Point(windows[i].x + step, windows[i].y);
		}
	}
	std::size_t kept = 0;
	for (std::size_t k = 0; k < nLive; k++)
		if (alive[live[k].grid]) live[kept++] = live[k];
	return kept;
}

}  // namespace semnav
