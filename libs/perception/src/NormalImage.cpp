/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/core/bits_math.h>
#include <semnav/common/ConfigChecks.h>
#include <semnav/common/Error.h>
#include <semnav/perception/NormalImage.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/core/hal/intrin.hpp>

#include "SimdKernels.h"

namespace semnav
{
namespace
{
/** Floats per vector of the widest SIMD the build allows. */
constexpr int kLanes = cv::v_float32::nlanes;
}  // namespace

using mrpt::DEG2RAD;
using mrpt::RAD2DEG;

void NormalImage::TOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& c, const std::string& s)
{
	checkKnownKeys(
	    c, s,
	    {"min_neighbour_distance_m", "max_neighbour_distance_m",
	     "min_pair_angle_deg"});
	minNeighbourDistance = readChecked(
	    c, s, "min_neighbour_distance_m", minNeighbourDistance, 0, 1);
	maxNeighbourDistance = readChecked(
	    c, s, "max_neighbour_distance_m", maxNeighbourDistance, 1e-4, 10);
	minPairAngle = DEG2RAD(
	    readChecked(c, s, "min_pair_angle_deg", RAD2DEG(minPairAngle), 0, 45));
	if (minNeighbourDistance >= maxNeighbourDistance)
		throw ConfigError(
		    "[" + s +
		    "] min_neighbour_distance_m must be below "
		    "max_neighbour_distance_m");
}

void NormalImage::TOptions::saveToConfigFile(
    mrpt::config::CConfigFileBase& c, const std::string& s) const
{
	c.write(s, "min_neighbour_distance_m", minNeighbourDistance);
	c.write(s, "max_neighbour_distance_m", maxNeighbourDistance);
	c.write(s, "min_pair_angle_deg", RAD2DEG(minPairAngle));
}

NormalImage::NormalImage() : NormalImage(TOptions()) {}

NormalImage::NormalImage(const TOptions& options) : m_options(options) {}

void NormalImage::compute(const Sweep& sweep)
{
	const int rows = static_cast<int>(sweep.rows());
	const int cols = static_cast<int>(sweep.cols());
	constexpr float nan = std::numeric_limits<float>::quiet_NaN();
	m_points.create(rows, cols, CV_32FC3);
	m_ranges.create(rows, cols, CV_32F);
	m_pointMask.create(rows, cols, CV_8U);
	m_normals.create(rows, cols, CV_32FC3);
	m_normalMask.create(rows, cols, CV_8U);
	m_sensorPos.assign(static_cast<std::size_t>(rows), cv::Vec3f(0, 0, 0));
	m_validPoints = m_validNormals = 0;
	if (rows == 0 || cols == 0) return;

	// Points: p = t + d (cos phi R.col(0) + sin phi R.col(1)) for the row's
	// scanner pose (R, t); the same as Sweep::point() without the per-pixel
	// pose composition. Also kept as padded planes (one invalid pixel
	// around) for the branch-free normal kernel below.
	const int pc = cols + 2;
	const std::size_t plane = static_cast<std::size_t>(rows + 2) * pc;
	// (The normal kernel reads up to kNormalKernelPad floats past the last
	// row.) Every interior pixel is written below; the padding stays 0 once
	// zeroed.
	const std::size_t padded = plane + 2 * detail::kNormalKernelPad;
	if (m_x.size() != padded || m_paddedCols != pc)
	{
		m_x.assign(padded, 0.0f);
		m_y.assign(padded, 0.0f);
		m_z.assign(padded, 0.0f);
		m_v.assign(padded, 0.0f);
		m_paddedCols = pc;
	}
	std::vector<float> cphi(cols), sphi(cols);
	for (int c = 0; c < cols; c++)
	{
		cphi[c] = static_cast<float>(std::cos(sweep.phi(c)));
		sphi[c] = static_cast<float>(std::sin(sweep.phi(c)));
	}
	const float* rng = sweep.ranges().data();
	const uint8_t* val = sweep.validity().data();
	const float fmax = std::numeric_limits<float>::max();
	for (int r = 0; r < rows; r++)
	{
		const auto& pose = sweep.sensorPose(r);
		const auto& R = pose.getRotationMatrix();
		const float a0 = static_cast<float>(R(0, 0)),
		            a1 = static_cast<float>(R(1, 0)),
		            a2 = static_cast<float>(R(2, 0));
		const float b0 = static_cast<float>(R(0, 1)),
		            b1 = static_cast<float>(R(1, 1)),
		            b2 = static_cast<float>(R(2, 1));
		const cv::Vec3f t(
		    static_cast<float>(pose.x()), static_cast<float>(pose.y()),
		    static_cast<float>(pose.z()));
		m_sensorPos[r] = t;
		auto* P = m_points.ptr<cv::Vec3f>(r);
		auto* M = m_pointMask.ptr<uint8_t>(r);
		float* D = m_ranges.ptr<float>(r);
		const std::size_t o = static_cast<std::size_t>(r + 1) * pc + 1;
		const float* rr = rng + static_cast<std::size_t>(r) * cols;
		const uint8_t* vv = val + static_cast<std::size_t>(r) * cols;
		float* X = &m_x[o];
		float* Y = &m_y[o];
		float* Z = &m_z[o];
		float* V = &m_v[o];
		// Branch-free (vectorizes): invalid, NaN, infinite or <= 0 ranges
		// give 0 in the padded planes and NaN in the outputs.
		for (int c = 0; c < cols; c++)
		{
			const float d = rr[c];
			const bool ok = (vv[c] != 0) & (d > 0.0f) & (d <= fmax);
			const float dd = ok ? d : 0.0f;
			const float u = dd * cphi[c], v = dd * sphi[c];
			X[c] = ok ? t[0] + u * a0 + v * b0 : 0.0f;
			Y[c] = ok ? t[1] + u * a1 + v * b1 : 0.0f;
			Z[c] = ok ? t[2] + u * a2 + v * b2 : 0.0f;
			V[c] = ok ? 1.0f : 0.0f;
			D[c] = ok ? d : nan;
			M[c] = ok ? 1 : 0;
		}
		// Interleaved points, NaN where invalid, kLanes at a time.
		const cv::v_float32 vNan = cv::vx_setall_f32(nan),
		                    vHalf = cv::vx_setall_f32(0.5f);
		float* Pf = P[0].val;
		int c = 0;
		for (; c + kLanes <= cols; c += kLanes)
		{
			const cv::v_float32 ok = cv::vx_load(V + c) > vHalf;
			cv::v_store_interleave(
			    Pf + 3 * c, cv::v_select(ok, cv::vx_load(X + c), vNan),
			    cv::v_select(ok, cv::vx_load(Y + c), vNan),
			    cv::v_select(ok, cv::vx_load(Z + c), vNan));
		}
		for (; c < cols; c++)
			P[c] =
			    M[c] ? cv::Vec3f(X[c], Y[c], Z[c]) : cv::Vec3f(nan, nan, nan);
		for (c = 0; c < cols; c++) m_validPoints += M[c];
	}

	// Normals (SimdKernels.h: the widest vectors the CPU has).
	detail::NormalKernelArgs a;
	a.rows = rows;
	a.cols = cols;
	a.x = &m_x[0];
	a.y = &m_y[0];
	a.z = &m_z[0];
	a.valid = &m_v[0];
	a.paddedCols = pc;
	a.sensor = m_sensorPos[0].val;
	a.e0sq = static_cast<float>(
	    m_options.minNeighbourDistance * m_options.minNeighbourDistance);
	a.e1sq = static_cast<float>(
	    m_options.maxNeighbourDistance * m_options.maxNeighbourDistance);
	const float sinMin = static_cast<float>(std::sin(m_options.minPairAngle));
	a.sinMinSq = sinMin * sinMin;
	m_nx.resize(cols + detail::kNormalKernelPad);
	m_ny.resize(cols + detail::kNormalKernelPad);
	m_nz.resize(cols + detail::kNormalKernelPad);
	a.nx = m_nx.data();
	a.ny = m_ny.data();
	a.nz = m_nz.data();
	a.normals = m_normals.ptr<float>(0);
	a.normalsStep = m_normals.step1();
	a.mask = m_normalMask.ptr<uint8_t>(0);
	a.maskStep = m_normalMask.step1();
	m_validNormals = detail::simdKernels().computeNormals(a);
}

void NormalImage::swapOutputs(
    cv::Mat& points, cv::Mat& pointMask, cv::Mat& normals, cv::Mat& normalMask)
{
	cv::swap(m_points, points);
	cv::swap(m_pointMask, pointMask);
	cv::swap(m_normals, normals);
	cv::swap(m_normalMask, normalMask);
}

cv::Vec3b NormalImage::rgbOf(const cv::Vec3f& n)
{
	auto ch = [](float v)
	{
		return static_cast<uint8_t>(std::clamp(
		    static_cast<int>(std::lround(128.0f + 127.0f * v)), 0, 255));
	};
	// Paper's frame: x right, y forward, z up (DESIGN.md).
	return cv::Vec3b(ch(-n[1]), ch(n[0]), ch(n[2]));
}

cv::Mat NormalImage::toBgr(const cv::Mat& normals, const cv::Mat& mask)
{
	cv::Mat out(normals.rows, normals.cols, CV_8UC3, cv::Scalar::all(0));
	for (int r = 0; r < normals.rows; r++)
	{
		const auto* N = normals.ptr<cv::Vec3f>(r);
		const auto* NM = mask.ptr<uint8_t>(r);
		auto* O = out.ptr<cv::Vec3b>(r);
		for (int c = 0; c < normals.cols; c++)
		{
			if (!NM[c]) continue;
			const cv::Vec3b rgb = rgbOf(N[c]);
			O[c] = cv::Vec3b(rgb[2], rgb[1], rgb[0]);
		}
	}
	return out;
}

void NormalImage::smoothed(
    const cv::Mat& groups, int halfWidth, cv::Mat& out) const
{
	const int rows = m_normals.rows, cols = m_normals.cols;
	out.create(rows, cols, CV_32FC3);
	const bool useGroups = !groups.empty();
	const int k = std::max(0, halfWidth);
	for (int r = 0; r < rows; r++)
	{
		auto* O = out.ptr<cv::Vec3f>(r);
		const auto* NM = m_normalMask.ptr<uint8_t>(r);
		const int* G = useGroups ? groups.ptr<int>(r) : nullptr;
		for (int c = 0; c < cols; c++)
		{
			O[c] = cv::Vec3f(0, 0, 0);
			if (!NM[c]) continue;
			const int g = useGroups ? G[c] : 0;
			cv::Vec3f sum(0, 0, 0);
			for (int rr = std::max(0, r - k); rr <= std::min(rows - 1, r + k);
			     rr++)
			{
				const auto* N2 = m_normals.ptr<cv::Vec3f>(rr);
				const auto* NM2 = m_normalMask.ptr<uint8_t>(rr);
				const int* G2 = useGroups ? groups.ptr<int>(rr) : nullptr;
				for (int cc = std::max(0, c - k);
				     cc <= std::min(cols - 1, c + k); cc++)
					if (NM2[cc] && (!useGroups || G2[cc] == g)) sum += N2[cc];
			}
			const float len = std::sqrt(sum.dot(sum));
			O[c] = len > 1e-12f ? sum * (1.0f / len)
			                    : m_normals.at<cv::Vec3f>(r, c);
		}
	}
}

}  // namespace semnav
