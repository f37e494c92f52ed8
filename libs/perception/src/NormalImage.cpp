/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/core/bits_math.h>
#include <semnav/common/Error.h>
#include <semnav/common/OptionTable.h>
#include <semnav/perception/NormalImage.h>

#include <algorithm>
#include <cmath>

#include "SimdKernels.h"

namespace semnav
{

namespace
{
using O = NormalImage::TOptions;
const OptionTable<O>& optionTable()
{
	static const auto t =
	    OptionTable<O>()
	        .real(
	            "min_neighbour_distance_m", &O::minNeighbourDistance, 0, 1,
	            "The paper's eps0: closer neighbours are rejected.")
	        .real(
	            "max_neighbour_distance_m", &O::maxNeighbourDistance, 1e-4, 10,
	            "The paper's eps1: farther neighbours are rejected.")
	        .angle(
	            "min_pair_angle_deg", &O::minPairAngle, 0, 45,
	            "Edge vector pairs closer to (anti)parallel are skipped.")
	        .integer(
	            "side_row_step_max", &O::sideRowStepMax, 0, 64,
	            "Side columns take row neighbours floor(1/|cos phi|) rows "
	            "away, at most this many (0 or 1: off).")
	        .check(
	            [](const O& o)
	            { return o.minNeighbourDistance < o.maxNeighbourDistance; },
	            "min_neighbour_distance_m must be below "
	            "max_neighbour_distance_m");
	return t;
}
}  // namespace

SEMNAV_OPTIONS_FROM_TABLE(NormalImage::TOptions, optionTable())

NormalImage::NormalImage() : NormalImage(TOptions()) {}

NormalImage::NormalImage(const TOptions& options) : m_options(options) {}

void NormalImage::compute(const Sweep& sweep)
{
	const int rows = static_cast<int>(sweep.rows());
	const int cols = static_cast<int>(sweep.cols());
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
	const detail::SimdKernels& K = detail::simdKernels();
	detail::PointRowArgs pa;
	pa.cols = cols;
	pa.cosPhi = cphi.data();
	pa.sinPhi = sphi.data();
	for (int r = 0; r < rows; r++)
	{
		const auto& pose = sweep.sensorPose(r);
		const auto& R = pose.getRotationMatrix();
		for (int k = 0; k < 3; k++)
		{
			pa.a[k] = static_cast<float>(R(k, 0));
			pa.b[k] = static_cast<float>(R(k, 1));
		}
		pa.t[0] = static_cast<float>(pose.x());
		pa.t[1] = static_cast<float>(pose.y());
		pa.t[2] = static_cast<float>(pose.z());
		m_sensorPos[r] = cv::Vec3f(pa.t[0], pa.t[1], pa.t[2]);
		const std::size_t o = static_cast<std::size_t>(r + 1) * pc + 1;
		pa.ranges = sweep.ranges().data() + static_cast<std::size_t>(r) * cols;
		pa.validity =
		    sweep.validity().data() + static_cast<std::size_t>(r) * cols;
		pa.x = &m_x[o];
		pa.y = &m_y[o];
		pa.z = &m_z[o];
		pa.valid = &m_v[o];
		pa.rangesOut = m_ranges.ptr<float>(r);
		pa.mask = m_pointMask.ptr<uint8_t>(r);
		pa.points = m_points.ptr<float>(r);
		m_validPoints += K.pointsRow(pa);
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
	m_validNormals = K.computeNormals(a);
	if (m_options.sideRowStepMax > 1) widenSideNormals(sweep, a);
}

namespace
{
/** The kernel's normal (SimdKernels.impl.h) from the given neighbours of
 * padded-plane index `i`, scalar; false where it has none. */
bool normalFrom(
    const detail::NormalKernelArgs& a, std::size_t i, const std::size_t* nb,
    const float* sensor, float* n)
{
	float ex[4], ey[4], ez[4], el[4];
	for (int k = 0; k < 4; k++)
	{
		const std::size_t j = nb[k];
		const float dx = a.x[j] - a.x[i], dy = a.y[j] - a.y[i],
		            dz = a.z[j] - a.z[i];
		const float d2 = dx * dx + dy * dy + dz * dz;
		const bool ok =
		    a.valid[j] * a.valid[i] > 0.5f && d2 >= a.e0sq && d2 <= a.e1sq;
		ex[k] = ok ? dx : 0.0f;
		ey[k] = ok ? dy : 0.0f;
		ez[k] = ok ? dz : 0.0f;
		el[k] = ok ? d2 : 0.0f;
	}
	const float vx = sensor[0] - a.x[i], vy = sensor[1] - a.y[i],
	            vz = sensor[2] - a.z[i];
	float nx = 0, ny = 0, nz = 0;
	for (int p = 0; p < 3; p++)
		for (int q = p + 1; q < 4; q++)
		{
			const float cx = ey[p] * ez[q] - ez[p] * ey[q];
			const float cy = ez[p] * ex[q] - ex[p] * ez[q];
			const float cz = ex[p] * ey[q] - ey[p] * ex[q];
			if (!(cx * cx + cy * cy + cz * cz > a.sinMinSq * el[p] * el[q]))
				continue;
			const float sgn = cx * vx + cy * vy + cz * vz >= 0 ? 1.0f : -1.0f;
			nx += sgn * cx;
			ny += sgn * cy;
			nz += sgn * cz;
		}
	const float l2 = nx * nx + ny * ny + nz * nz;
	if (!(l2 > 1e-24f)) return false;
	const float inv = 1.0f / std::sqrt(l2);
	n[0] = nx * inv;
	n[1] = ny * inv;
	n[2] = nz * inv;
	return true;
}
}  // namespace

void NormalImage::widenSideNormals(
    const Sweep& sweep, const detail::NormalKernelArgs& a)
{
	m_normals.copyTo(m_sideNormals);
	m_normalMask.copyTo(m_sideNormalMask);
	const int rows = m_normals.rows, cols = m_normals.cols;
	const int pc = m_paddedCols;
	auto at = [&](int rr, int cc)
	{
		return static_cast<std::size_t>(rr + 1) * pc +
		       static_cast<std::size_t>(cc + 1);
	};
	for (int c = 0; c < cols; c++)
	{
		const double cp = std::abs(std::cos(sweep.phi(c)));
		const int step =
		    cp > 1e-9
		        ? static_cast<int>(std::min(
		              1.0 / cp, static_cast<double>(m_options.sideRowStepMax)))
		        : m_options.sideRowStepMax;
		if (step < 2) continue;
		for (int r = 0; r < rows; r++)
		{
			// Rows r - down and r + up (the padded planes' border row
			// stands for "none" where the sweep ends at r).
			const int down = r == 0 ? 1 : std::min(step, r);
			const int up = r == rows - 1 ? 1 : std::min(step, rows - 1 - r);
			const std::size_t nb[4] = {
			    at(r - down, c - 1), at(r - down, c + 1), at(r + up, c - 1),
			    at(r + up, c + 1)};
			float n[3];
			const bool ok = normalFrom(
			    a, at(r, c), nb, m_sensorPos[static_cast<std::size_t>(r)].val,
			    n);
			m_sideNormals.at<cv::Vec3f>(r, c) =
			    ok ? cv::Vec3f(n[0], n[1], n[2]) : cv::Vec3f(0, 0, 0);
			m_sideNormalMask.at<uint8_t>(r, c) = ok ? 1 : 0;
		}
	}
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
	// Paper's frame: x right, y forward, z up (docs/design.md).
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
	const cv::Mat& normals = classifierNormals();
	const cv::Mat& mask = classifierNormalMask();
	const int rows = normals.rows, cols = normals.cols;
	out.create(rows, cols, CV_32FC3);
	const bool useGroups = !groups.empty();
	const int k = std::max(0, halfWidth);
	for (int r = 0; r < rows; r++)
	{
		auto* O = out.ptr<cv::Vec3f>(r);
		const auto* NM = mask.ptr<uint8_t>(r);
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
				const auto* N2 = normals.ptr<cv::Vec3f>(rr);
				const auto* NM2 = mask.ptr<uint8_t>(rr);
				const int* G2 = useGroups ? groups.ptr<int>(rr) : nullptr;
				for (int cc = std::max(0, c - k);
				     cc <= std::min(cols - 1, c + k); cc++)
					if (NM2[cc] && (!useGroups || G2[cc] == g)) sum += N2[cc];
			}
			const float len = std::sqrt(sum.dot(sum));
			O[c] =
			    len > 1e-12f ? sum * (1.0f / len) : normals.at<cv::Vec3f>(r, c);
		}
	}
}

}  // namespace semnav
