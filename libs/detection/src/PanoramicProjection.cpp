/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/Error.h>
#include <semnav/detection/PanoramicProjection.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace semnav
{
namespace
{
/** Whether the panoramic position `f` lies in `box` (left and top edges
 * included). */
bool inBox(const cv::Rect2d& box, const cv::Vec2f& f)
{
	return f[0] >= box.x && f[0] < box.x + box.width && f[1] >= box.y &&
	       f[1] < box.y + box.height;
}

/** Fractional index of x in increasing v; -1 outside. */
float fractionalIndex(const std::vector<double>& v, double x)
{
	if (v.size() < 2 || x < v.front() || x > v.back()) return -1.f;
	const auto it = std::upper_bound(v.begin(), v.end(), x);
	if (it == v.end()) return static_cast<float>(v.size() - 1);
	const std::size_t i = static_cast<std::size_t>(it - v.begin()) - 1;
	const double d = v[i + 1] - v[i];
	return static_cast<float>(double(i) + (d > 0 ? (x - v[i]) / d : 0.0));
}
}  // namespace

PanoramicProjection::PanoramicProjection(
    const std::vector<double>& phis, const std::vector<double>& thetas)
    : m_phis(phis), m_thetas(thetas)
{
	const int cols = static_cast<int>(phis.size());
	const int rows = static_cast<int>(thetas.size());
	if (cols < 2 || rows < 2) return;
	for (std::size_t i = 1; i < phis.size(); i++)
		if (!(phis[i] > phis[i - 1]))
			throw Error("PanoramicProjection: bearings must increase");
	for (std::size_t i = 1; i < thetas.size(); i++)
		if (!(thetas[i] >= thetas[i - 1]))
			throw Error("PanoramicProjection: tilts must not decrease");
	m_size = cv::Size(cols, rows);
	const double az0 = phis.front(), daz = (phis.back() - az0) / (cols - 1);
	const double el0 = thetas.front(),
	             del = (thetas.back() - el0) / std::max(1, rows - 1);
	m_forward.create(rows, cols, CV_32FC2);
	for (int r = 0; r < rows; r++)
	{
		const double th = thetas[std::size_t(r)];
		auto* f = m_forward.ptr<cv::Vec2f>(r);
		for (int c = 0; c < cols; c++)
		{
			const double ph = phis[std::size_t(c)];
			const double az =
			    std::atan2(std::sin(ph), std::cos(ph) * std::cos(th));
			const double el = std::asin(std::cos(ph) * std::sin(th));
			f[c] = cv::Vec2f(
			    static_cast<float>((az - az0) / daz),
			    static_cast<float>(del > 0 ? (el - el0) / del : 0.0));
		}
	}
	m_invX.create(rows, cols, CV_32FC1);
	m_invY.create(rows, cols, CV_32FC1);
	for (int v = 0; v < rows; v++)
	{
		const double el = el0 + del * v;
		auto* X = m_invX.ptr<float>(v);
		auto* Y = m_invY.ptr<float>(v);
		for (int u = 0; u < cols; u++)
		{
			const double az = az0 + daz * u;
			const double ph = std::asin(std::cos(el) * std::sin(az));
			const double th =
			    std::atan2(std::sin(el), std::cos(el) * std::cos(az));
			const float c = fractionalIndex(phis, ph);
			const float r = fractionalIndex(thetas, th);
			X[u] = (c < 0 || r < 0) ? -1.f : c;
			Y[u] = (c < 0 || r < 0) ? -1.f : r;
		}
	}
	// cv::remap's nearest neighbours, by remapping the pixel indices
	// (exact in float below 2^24).
	if (rows * cols < (1 << 24))
	{
		cv::Mat index(rows, cols, CV_32F), nearest;
		for (int i = 0; i < rows * cols; i++) index.at<float>(i) = float(i);
		cv::remap(
		    index, nearest, m_invX, m_invY, cv::INTER_NEAREST,
		    cv::BORDER_CONSTANT, cv::Scalar::all(-1));
		nearest.convertTo(m_nearest, CV_32S);
	}
	cv::convertMaps(m_invX, m_invY, m_fixedXY, m_fixedA, CV_16SC2);
	m_rowMonotonic.assign(std::size_t(rows), 1);
	for (int r = 0; r < rows; r++)
	{
		const auto* f = m_forward.ptr<cv::Vec2f>(r);
		for (int c = 1; c < cols; c++)
			if (f[c][0] < f[c - 1][0]) m_rowMonotonic[std::size_t(r)] = 0;
	}
	const int bw = (cols + kBlock - 1) / kBlock,
	          bh = (rows + kBlock - 1) / kBlock;
	m_blockBounds.create(bh, bw, CV_32FC4);
	m_blockBounds.setTo(cv::Scalar(1e9f, 1e9f, -1e9f, -1e9f));
	for (int v = 0; v < rows; v++)
	{
		const auto* X = m_invX.ptr<float>(v);
		const auto* Y = m_invY.ptr<float>(v);
		auto* b = m_blockBounds.ptr<cv::Vec4f>(v / kBlock);
		for (int u = 0; u < cols; u++)
		{
			if (X[u] < 0) continue;
			cv::Vec4f& bb = b[u / kBlock];
			bb[0] = std::min(bb[0], X[u]);
			bb[1] = std::min(bb[1], Y[u]);
			bb[2] = std::max(bb[2], X[u]);
			bb[3] = std::max(bb[3], Y[u]);
		}
	}
}

bool PanoramicProjection::sameGrid(
    const std::vector<double>& phis, const std::vector<double>& thetas) const
{
	return !empty() && phis == m_phis && thetas == m_thetas;
}

cv::Mat PanoramicProjection::toPanoramic(
    const cv::Mat& sweepImage, int interpolation) const
{
	if (sweepImage.size() != m_size)
		throw Error("PanoramicProjection: image size differs from the grid");
	cv::Mat out;
	if (interpolation == cv::INTER_NEAREST && !m_nearest.empty() &&
	    sweepImage.isContinuous())
	{
		// The same copies as cv::remap, without its per-pixel rounding.
		out.create(m_size, sweepImage.type());
		const int32_t* idx = m_nearest.ptr<int32_t>();
		const int n = m_size.area();
		const auto copy = [&](auto zero)
		{
			using T = decltype(zero);
			const T* src = sweepImage.ptr<T>();
			T* dst = out.ptr<T>();
			for (int i = 0; i < n; i++)
				dst[i] = idx[i] < 0 ? zero : src[idx[i]];
		};
		switch (sweepImage.elemSize())
		{
			case 1:
				copy(uint8_t(0));
				return out;
			case 2:
				copy(uint16_t(0));
				return out;
			case 4:
				copy(uint32_t(0));
				return out;
			case 8:
				copy(uint64_t(0));
				return out;
			default:
				break;
		}
	}
	if (interpolation == cv::INTER_LINEAR)
		cv::remap(
		    sweepImage, out, m_fixedXY, m_fixedA, interpolation,
		    cv::BORDER_CONSTANT, cv::Scalar::all(0));
	else
		cv::remap(
		    sweepImage, out, m_invX, m_invY, interpolation, cv::BORDER_CONSTANT,
		    cv::Scalar::all(0));
	return out;
}

cv::Rect PanoramicProjection::sourceRegion(const cv::Rect2d& box) const
{
	if (empty()) return {};
	const cv::Rect pano = cv::Rect(
	                          static_cast<int>(std::floor(box.x)),
	                          static_cast<int>(std::floor(box.y)),
	                          static_cast<int>(std::ceil(box.width)) + 1,
	                          static_cast<int>(std::ceil(box.height)) + 1) &
	                      cv::Rect(0, 0, m_size.width, m_size.height);
	if (pano.empty()) return {};
	// The bounds of the blocks the box touches hold those of its pixels.
	float x0 = 1e9f, y0 = 1e9f, x1 = -1e9f, y1 = -1e9f;
	for (int bv = pano.y / kBlock; bv <= (pano.br().y - 1) / kBlock; bv++)
	{
		const auto* b = m_blockBounds.ptr<cv::Vec4f>(bv);
		for (int bu = pano.x / kBlock; bu <= (pano.br().x - 1) / kBlock; bu++)
		{
			x0 = std::min(x0, b[bu][0]);
			y0 = std::min(y0, b[bu][1]);
			x1 = std::max(x1, b[bu][2]);
			y1 = std::max(y1, b[bu][3]);
		}
	}
	if (x1 < x0) return {};
	const int c0 = std::max(0, static_cast<int>(x0) - 3),
	          c1 = std::min(m_size.width - 1, static_cast<int>(x1) + 4);
	const int r0 = std::max(0, static_cast<int>(y0) - 3),
	          r1 = std::min(m_size.height - 1, static_cast<int>(y1) + 4);
	return {c0, r0, c1 - c0 + 1, r1 - r0 + 1};
}

std::pair<int, int> PanoramicProjection::columnsIn(
    int r, const cv::Rect& src, const cv::Rect2d& box) const
{
	const auto* f = m_forward.ptr<cv::Vec2f>(r);
	if (!m_rowMonotonic[std::size_t(r)]) return {src.x, src.x + src.width};
	const auto first = std::partition_point(
	    f + src.x, f + src.x + src.width,
	    [&](const cv::Vec2f& v) { return !(v[0] >= box.x); });
	const auto last = std::partition_point(
	    first, f + src.x + src.width,
	    [&](const cv::Vec2f& v) { return v[0] < box.x + box.width; });
	return {static_cast<int>(first - f), static_cast<int>(last - f)};
}

std::vector<cv::Point> PanoramicProjection::sweepPixelsIn(
    const cv::Rect2d& box) const
{
	std::vector<cv::Point> out, none;
	sweepPixelsIn(box, cv::Rect2d(), out, none);
	return out;
}

void PanoramicProjection::sweepPixelsIn(
    const cv::Rect2d& box, const cv::Rect2d& inner,
    std::vector<cv::Point>& pixels, std::vector<cv::Point>& innerPixels) const
{
	pixels.clear();
	innerPixels.clear();
	const cv::Rect src = sourceRegion(box);
	// At most the source region (no reallocation while filling; callers
	// may keep `innerPixels` between calls).
	pixels.reserve(std::size_t(src.area()));
	for (int r = src.y; r < src.y + src.height; r++)
	{
		const auto* f = m_forward.ptr<cv::Vec2f>(r);
		const auto [c0, c1] = columnsIn(r, src, box);
		for (int c = c0; c < c1; c++)
		{
			if (!inBox(box, f[c])) continue;
			pixels.emplace_back(c, r);
			if (inBox(inner, f[c])) innerPixels.emplace_back(c, r);
		}
	}
}

}  // namespace semnav
