/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/core/format.h>
#include <semnav/common/Error.h>
#include <semnav/perception/RuleClassifier.h>

#include <array>
#include <chrono>
#include <cmath>
#include <string>
#include <utility>

#include "BoxSum.h"
#include "RuleClassifierDetail.h"

/* classify()'s stages, one file each: surfaces (RuleClassifierSurfaces.cpp),
 * coplanar groups and plane steps (RuleClassifierPlanes.cpp), the rules
 * (RuleClassifierRules.cpp), leftover pixels and ground types
 * (RuleClassifierPixels.cpp), regions (RuleClassifierRegions.cpp). */

namespace semnav
{
using namespace detail::rules;

namespace
{
/** Wall-clock durations of named stages, for the debug log. */
class StageTimes
{
public:
	/** Runs `stage` and records its duration under `name`. */
	template <class Stage>
	void run(const char* name, Stage&& stage)
	{
		const auto t0 = std::chrono::steady_clock::now();
		stage();
		const auto t1 = std::chrono::steady_clock::now();
		if (m_count < m_stages.size())
			m_stages[m_count++] = {
			    name,
			    std::chrono::duration<double, std::milli>(t1 - t0).count()};
	}
	/** "name ms name ms ...", ms to two decimals. */
	std::string summary() const
	{
		std::string s;
		for (std::size_t i = 0; i < m_count; i++)
			s += mrpt::format(
			    "%s%s %.2f", i ? " " : "", m_stages[i].first,
			    m_stages[i].second);
		return s;
	}

private:
	std::array<std::pair<const char*, double>, 16> m_stages;
	std::size_t m_count = 0;
};
}  // namespace

RuleClassifier::RuleClassifier() : RuleClassifier(TOptions()) {}

RuleClassifier::RuleClassifier(const TOptions& options)
    : mrpt::system::COutputLogger("RuleClassifier"), m_options(options)
{
}

cv::Mat RuleClassifier::surfaceIds() const
{
	if (m_surf.size() != static_cast<std::size_t>(m_rows * m_cols))
		return cv::Mat();
	return cv::Mat(m_rows, m_cols, CV_32S, const_cast<int*>(m_surf.data()));
}

cv::Mat RuleClassifier::orientationClasses() const
{
	if (m_class.size() != static_cast<std::size_t>(m_rows * m_cols))
		return cv::Mat();
	return cv::Mat(m_rows, m_cols, CV_8U, const_cast<uint8_t*>(m_class.data()));
}

cv::Mat RuleClassifier::planeSides() const
{
	if (m_side.size() != static_cast<std::size_t>(m_rows * m_cols))
		return cv::Mat();
	return cv::Mat(m_rows, m_cols, CV_8U, const_cast<uint8_t*>(m_side.data()));
}

void RuleClassifier::classify(
    const NormalImage& normals, const cv::Mat& areaIds,
    const Roughness& roughness, LabeledSweep& out, bool floorReferenced)
{
	if (!beginSweep(normals, areaIds, out)) return;
	StageTimes times;
	// 1. Orientation per pixel; 2. ground level.
	times.run("smooth+class", [&] { classifyOrientation(normals); });
	bool estimated = false;
	double zg = 0;
	times.run(
	    "ground", [&] { zg = estimateGround(floorReferenced, estimated); });
	out.groundZ = zg;
	out.groundEstimated = estimated;
	// 3. Surfaces: pieces of areas; coplanar vertical pieces of different
	// areas (a wall seen at a grazing angle floods into column strips)
	// grouped; groups split where their plane steps (a recessed door).
	times.run("pass1", [&] { buildPieces(); });
	times.run("merge", [&] { mergeCoplanar(); });
	times.run("split", [&] { splitPlanes(); });
	times.run("pass2", [&] { buildGroupSurfaces(); });
	// 4. Rules; 5. pixels; 6. indoor or outdoor ground.
	std::size_t ceilPixels = 0;
	times.run("rules", [&] { ceilPixels = applyRules(zg, out); });
	times.run("leftover", [&] { labelPixels(zg); });
	times.run(
	    "ground types", [&] { finishLabels(ceilPixels, roughness, out); });
	times.run("regions", [&] { buildRegions(out, roughness.rBar()); });
	MRPT_LOG_DEBUG_FMT("timing: %s", times.summary().c_str());
	MRPT_LOG_DEBUG_FMT(
	    "ground z=%.3f (%s), %zu surfaces, %zu regions, %s", zg,
	    estimated ? "estimated" : "configured", m_surfaces.size(),
	    out.regions.size(), out.indoor ? "indoor" : "outdoor");
}

bool RuleClassifier::beginSweep(
    const NormalImage& normals, const cv::Mat& areaIds, LabeledSweep& out)
{
	const TOptions& o = m_options;
	m_rows = normals.points().rows;
	m_cols = normals.points().cols;
	const int rows = m_rows, cols = m_cols, n = rows * cols;
	out.labels.create(rows, cols, CV_8U);
	out.labels.setTo(0);
	out.regionIds.create(rows, cols, CV_32S);
	out.regionIds.setTo(-1);
	out.regions.clear();
	out.groundZ = o.groundZ;
	out.groundEstimated = false;
	out.ceilingZ.reset();
	out.indoor = o.environment != TOptions::Environment::Outdoor;
	if (n == 0) return false;
	if (areaIds.rows != rows || areaIds.cols != cols ||
	    areaIds.type() != CV_32S)
		throw Error("RuleClassifier: area image does not match the sweep");

	if (m_rowOf.size() != static_cast<std::size_t>(n))
	{
		// Row and column of each pixel index (integer division is slow in
		// the per-pixel loops).
		m_rowOf.resize(n);
		m_colOf.resize(n);
		for (int p = 0; p < n; p++)
		{
			m_rowOf[p] = p / cols;
			m_colOf[p] = p % cols;
		}
	}
	m_points = &normals.points();
	m_pointMask = &normals.pointMask();
	m_ranges = &normals.ranges();
	m_areas = &areaIds;
	return true;
}

void RuleClassifier::classifyOrientation(const NormalImage& normals)
{
	const TOptions& o = m_options;
	const int rows = m_rows, cols = m_cols, n = rows * cols;
	const auto* PM = m_pointMask->ptr<uint8_t>(0);
	const auto* NM = normals.classifierNormalMask().ptr<uint8_t>(0);
	// (A box filter over all pixels: 0 where there is no normal; pixels
	// without their own normal are not classified anyway.)
	detail::OrientThresholds th;
	th.cosUp = static_cast<float>(std::cos(o.groundNormalTolerance));
	th.cosDown = static_cast<float>(std::cos(o.ceilingNormalTolerance));
	th.sinVert = static_cast<float>(std::sin(o.wallNormalTolerance));
	const detail::SimdKernels& K = detail::simdKernels();
	m_class.resize(n);
	auto classifyRow = [&](int r, const float* N)
	{
		const int base = r * cols;
		K.orientRow(N, PM + base, NM + base, &m_class[base], cols, th);
	};
	if (o.normalSmoothingHalfWidth > 0)
	{
		// Box sums normalised and classified row by row.
		m_smoothSum.create(rows, cols, CV_32FC3);
		detail::boxSumRows(
		    normals.classifierNormals(), o.normalSmoothingHalfWidth, m_tmp,
		    [&](int r) { return m_smoothSum.ptr<float>(r); },
		    [&](int r, const float*)
		    {
			    float* S = m_smoothSum.ptr<float>(r);
			    K.normalizeRow(S, cols);
			    classifyRow(r, S);
		    });
		m_ns = &m_smoothSum;
	}
	else
	{
		m_ns = &normals.classifierNormals();
		for (int r = 0; r < rows; r++) classifyRow(r, m_ns->ptr<float>(r));
	}
}

double RuleClassifier::estimateGround(
    bool floorReferenced, bool& estimated) const
{
	estimated = false;
	if (!m_options.autoGroundLevel) return m_options.groundZ;
	constexpr double binSize = 0.02, zMin = -50.0;
	constexpr int bins = 5000;
	std::vector<int> hist(bins, 0);
	std::vector<double> zsum(bins, 0.0);
	const auto* P = m_points->ptr<cv::Vec3f>(0);
	const int n = m_rows * m_cols;
	const float zLo = floorReferenced
	                      ? m_options.groundZ - m_options.groundSearch
	                      : -HUGE_VALF,
	            zHi = floorReferenced
	                      ? m_options.groundZ + m_options.groundSearch
	                      : HUGE_VALF;
	int total = 0;
	for (int p = 0; p < n; p++)
		if (m_class[p] == kUp && P[p][2] >= zLo && P[p][2] <= zHi)
		{
			const int b = static_cast<int>((P[p][2] - zMin) / binSize);
			if (b >= 0 && b < bins)
			{
				hist[b]++;
				zsum[b] += P[p][2];
				total++;
			}
		}
	if (total < m_options.minGroundPixels) return m_options.groundZ;
	// Window sums over +-2 bins (10 cm): rough ground spreads over bins.
	std::vector<int> win(bins, 0);
	int best = 0;
	for (int b = 0; b < bins; b++)
	{
		for (int k = std::max(0, b - 2); k <= std::min(bins - 1, b + 2); k++)
			win[b] += hist[k];
		best = std::max(best, win[b]);
	}
	// The lowest local maximum with a fair share of the support: the floor,
	// not a larger table top or a terrace further up. Its height: the mean
	// of the points in its window.
	const int need =
	    std::max(m_options.minGroundPixels, static_cast<int>(0.3 * best));
	for (int b = 0; b < bins; b++)
	{
		if (win[b] < need) continue;
		if (b > 0 && win[b - 1] > win[b]) continue;
		if (b + 1 < bins && win[b + 1] > win[b]) continue;
		double sum = 0;
		int cnt = 0;
		for (int k = std::max(0, b - 2); k <= std::min(bins - 1, b + 2); k++)
		{
			sum += zsum[k];
			cnt += hist[k];
		}
		if (cnt == 0) break;
		estimated = true;
		return sum / cnt;
	}
	return m_options.groundZ;
}

void RuleClassifier::finishLabels(
    std::size_t ceilPixels, const Roughness& roughness, LabeledSweep& out)
{
	const TOptions& o = m_options;
	const int n = m_rows * m_cols;
	if (o.environment == TOptions::Environment::Auto)
		out.indoor =
		    ceilPixels >= static_cast<std::size_t>(o.indoorMinCeilingPixels);
	uint8_t* L = out.labels.ptr<uint8_t>(0);
	for (int p = 0; p < n; p++)
		L[p] = m_label[p] == kNoLabel ? 0 : static_cast<uint8_t>(m_label[p]);
	if (!out.indoor) labelGroundTypes(roughness, out);
}

}  // namespace semnav
