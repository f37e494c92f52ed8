/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/cascade/CascadeError.h>
#include <semnav/cascade/CascadeEvaluator.h>

#include <cstddef>

#include "CompiledFeature.h"

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
    : m_cascade(std::move(o.m_cascade)),
      m_compiled(std::move(o.m_compiled)),
      m_stride(o.m_stride),
      m_own(std::move(o.m_own)),
      m_ii(o.m_ii == &o.m_own ? &m_own : o.m_ii)
{
}
CascadeEvaluator& CascadeEvaluator::operator=(CascadeEvaluator&& o) noexcept
{
	m_cascade = std::move(o.m_cascade);
	m_compiled = std::move(o.m_compiled);
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
	const int stride = m_ii->sum().cols;
	if (stride == m_stride) return;
	m_compiled.clear();
	m_compiled.reserve(m_cascade.features.size());
	for (const auto& f : m_cascade.features) m_compiled.emplace_back(f, stride);
	m_stride = stride;
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
	        sum, sq, ii.sum().cols, ii.sqsum().cols, win, nf))
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

}  // namespace semnav
