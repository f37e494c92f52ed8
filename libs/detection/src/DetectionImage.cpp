/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/Error.h>
#include <semnav/detection/DetectionImage.h>
#include <semnav/perception/NormalImage.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

namespace semnav
{
namespace
{
/** NormalImage::rgbOf's channel, clamp(lround(128 + 127 v), 0, 255), bit
 * for bit: the same float 128 + 127 v, rounded half away from zero as
 * floor(x + 0.5) in double (exact for a float; only x >= 0 survives the
 * clamp, where the two roundings agree), the floor of a positive value by
 * truncation (no libm call). */
inline uint8_t channelOf(float v)
{
	const float x = 128.0f + 127.0f * v;
	const double y = static_cast<double>(x) + 0.5;
	if (!(y >= 1)) return 0;  // below 1 (also NaN, as lround's clamp)
	return y >= 255 ? 255 : static_cast<uint8_t>(static_cast<int>(y));
}
}  // namespace

const std::string& channelName(DetectionChannel c)
{
	static const std::string names[] = {"grey", "red", "green", "blue", "view"};
	return names[static_cast<int>(c)];
}

DetectionChannel channelFromName(const std::string& name)
{
	for (auto c :
	     {DetectionChannel::Grey, DetectionChannel::Red,
	      DetectionChannel::Green, DetectionChannel::Blue,
	      DetectionChannel::View})
		if (channelName(c) == name) return c;
	throw ConfigError(
	    "unknown detection channel '" + name +
	    "' (grey, red, green, blue, view)");
}

cv::Mat DetectionImage::fromNormals(
    const cv::Mat& normals, const cv::Mat& normalMask, DetectionChannel channel,
    int smoothing, const std::vector<double>& phis,
    const std::vector<double>& thetas)
{
	if (normals.type() != CV_32FC3 || normalMask.type() != CV_8UC1 ||
	    normals.size() != normalMask.size())
		throw Error(
		    "DetectionImage: expected CV_32FC3 normals and a CV_8U mask of "
		    "the same size");
	const bool view = channel == DetectionChannel::View;
	if (view && (phis.size() != static_cast<std::size_t>(normals.cols) ||
	             thetas.size() != static_cast<std::size_t>(normals.rows)))
		throw Error(
		    "DetectionImage: the view channel needs one bearing per column "
		    "and one tilt per row");
	return fromSmoothedNormals(
	    smoothNormals(normals, normalMask, smoothing), normalMask, channel,
	    view ? viewRotation(phis, thetas) : cv::Mat());
}

cv::Mat DetectionImage::smoothNormals(
    const cv::Mat& normals, const cv::Mat& normalMask, int smoothing)
{
	if (normals.type() != CV_32FC3 || normalMask.type() != CV_8UC1 ||
	    normals.size() != normalMask.size())
		throw Error(
		    "DetectionImage: expected CV_32FC3 normals and a CV_8U mask of "
		    "the same size");
	// Never written in place: `normals` belongs to the caller.
	if (smoothing <= 0) return normals;
	cv::Mat sm;
	cv::Mat masked(normals.size(), CV_32FC3, cv::Scalar::all(0));
	normals.copyTo(masked, normalMask);
	const int k = 2 * smoothing + 1;
	cv::boxFilter(
	    masked, sm, -1, cv::Size(k, k), cv::Point(-1, -1), false,
	    cv::BORDER_CONSTANT);
	for (int r = 0; r < sm.rows; r++)
	{
		auto* p = sm.ptr<cv::Vec3f>(r);
		for (int c = 0; c < sm.cols; c++)
		{
			const float len = std::sqrt(p[c].dot(p[c]));
			if (len > 1e-6f) p[c] *= 1.0f / len;
		}
	}
	return sm;
}

cv::Mat DetectionImage::viewRotation(
    const std::vector<double>& phis, const std::vector<double>& thetas)
{
	cv::Mat rot(
	    static_cast<int>(thetas.size()), static_cast<int>(phis.size()),
	    CV_32FC2);
	for (int r = 0; r < rot.rows; r++)
	{
		const double cosTheta = std::cos(thetas[std::size_t(r)]);
		auto* o = rot.ptr<cv::Vec2f>(r);
		for (int c = 0; c < rot.cols; c++)
		{
			// Turn by -azimuth of the line of sight (as
			// PanoramicProjection): x along the ray, y to its left.
			const double ph = phis[std::size_t(c)];
			const double az = std::atan2(std::sin(ph), std::cos(ph) * cosTheta);
			o[c] = cv::Vec2f(
			    static_cast<float>(std::cos(az)),
			    static_cast<float>(std::sin(az)));
		}
	}
	return rot;
}

cv::Mat DetectionImage::fromSmoothedNormals(
    const cv::Mat& sm, const cv::Mat& normalMask, DetectionChannel channel,
    const cv::Mat& rotation)
{
	const bool view = channel == DetectionChannel::View;
	if (view && (rotation.type() != CV_32FC2 || rotation.size() != sm.size()))
		throw Error(
		    "DetectionImage: the view channel needs the sweep's rotation "
		    "(one bearing per column and one tilt per row)");
	// One channel of NormalImage::rgbOf (r = -y, g = x, b = z) per pixel,
	// grey as cv::cvtColor(COLOR_BGR2GRAY) computes it for 8 bits in
	// OpenCV 4 (fixed point, 15 bits: 0.299, 0.587, 0.114 as 9798, 19235,
	// 3735; DetectionImage's test checks every colour), without the colour
	// image.
	cv::Mat out(sm.size(), CV_8U);
	for (int r = 0; r < sm.rows; r++)
	{
		const auto* n = sm.ptr<cv::Vec3f>(r);
		const auto* m = normalMask.ptr<uint8_t>(r);
		const auto* rot = view ? rotation.ptr<cv::Vec2f>(r) : nullptr;
		auto* o = out.ptr<uint8_t>(r);
		for (int c = 0; c < sm.cols; c++)
		{
			if (!m[c])
			{
				o[c] = 0;
				continue;
			}
			cv::Vec3f v = n[c];
			if (view)
			{
				const float ca = rot[c][0], sa = rot[c][1];
				v = cv::Vec3f(
				    ca * n[c][0] + sa * n[c][1], -sa * n[c][0] + ca * n[c][1],
				    n[c][2]);
			}
			switch (channel)
			{
				case DetectionChannel::Grey:
				case DetectionChannel::View:
					o[c] = static_cast<uint8_t>(
					    (channelOf(v[2]) * 3735 + channelOf(v[0]) * 19235 +
					     channelOf(-v[1]) * 9798 + (1 << 14)) >>
					    15);
					break;
				case DetectionChannel::Red:
					o[c] = channelOf(-v[1]);
					break;
				case DetectionChannel::Green:
					o[c] = channelOf(v[0]);
					break;
				case DetectionChannel::Blue:
					o[c] = channelOf(v[2]);
					break;
			}
		}
	}
	return out;
}

}  // namespace semnav
