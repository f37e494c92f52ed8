/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/Error.h>
#include <semnav/detection/DetectionImage.h>
#include <semnav/perception/NormalImage.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

namespace semnav
{
const std::string& channelName(DetectionChannel c)
{
	static const std::string names[] = {"grey", "red", "green", "blue"};
	return names[static_cast<int>(c)];
}

DetectionChannel channelFromName(const std::string& name)
{
	for (auto c :
	     {DetectionChannel::Grey, DetectionChannel::Red,
	      DetectionChannel::Green, DetectionChannel::Blue})
		if (channelName(c) == name) return c;
	throw ConfigError(
	    "unknown detection channel '" + name + "' (grey, red, green, blue)");
}

cv::Mat DetectionImage::fromNormals(
    const cv::Mat& normals, const cv::Mat& normalMask, DetectionChannel channel,
    int smoothing)
{
	if (normals.type() != CV_32FC3 || normalMask.type() != CV_8UC1 ||
	    normals.size() != normalMask.size())
		throw Error(
		    "DetectionImage: expected CV_32FC3 normals and a CV_8U mask of "
		    "the same size");
	// Never written in place: `normals` belongs to the caller.
	cv::Mat sm;
	if (smoothing <= 0)
		sm = normals;
	else
	{
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
	}
	cv::Mat bgr(normals.size(), CV_8UC3, cv::Scalar::all(0));
	for (int r = 0; r < normals.rows; r++)
	{
		const auto* n = sm.ptr<cv::Vec3f>(r);
		const auto* m = normalMask.ptr<uint8_t>(r);
		auto* o = bgr.ptr<cv::Vec3b>(r);
		for (int c = 0; c < normals.cols; c++)
		{
			if (!m[c]) continue;
			const cv::Vec3b rgb = NormalImage::rgbOf(n[c]);
			o[c] = cv::Vec3b(rgb[2], rgb[1], rgb[0]);
		}
	}
	cv::Mat out;
	switch (channel)
	{
		case DetectionChannel::Grey:
			cv::cvtColor(bgr, out, cv::COLOR_BGR2GRAY);
			break;
		case DetectionChannel::Red:
			cv::extractChannel(bgr, out, 2);
			break;
		case DetectionChannel::Green:
			cv::extractChannel(bgr, out, 1);
			break;
		case DetectionChannel::Blue:
			cv::extractChannel(bgr, out, 0);
			break;
	}
	return out;
}

}  // namespace semnav
