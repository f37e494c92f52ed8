/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <opencv2/core/mat.hpp>
#include <string>

namespace semnav
{
/** Which 8-bit image of the normal image the cascades see. The paper uses
 * the grey-scale version of the RGB normal image (sec. 2.2.2); the single
 * channels are R = 128 + 127 n_right, G = 128 + 127 n_forward, B = 128 +
 * 127 n_up (DESIGN.md). Pixels without a normal are 0 in every choice. */
enum class DetectionChannel
{
	Grey,
	Red,
	Green,
	Blue
};

/** "grey", "red", "green", "blue". */
const std::string& channelName(DetectionChannel c);
/** Parses a channel name; throws ConfigError listing the names. */
DetectionChannel channelFromName(const std::string& name);

/** Builds the detection image of a sweep from its normals, the same way for
 * training and detection. */
class DetectionImage
{
public:
	/** `normals` CV_32FC3 (robot frame, NormalImage::normals()),
	 * `normalMask` CV_8U; result CV_8UC1, sweep layout (row 0 = lowest
	 * tilt, col 0 = the robot's right). Grey is cv::cvtColor(BGR2GRAY) of
	 * the colour normal image (NormalImage::rgbOf). With `smoothing` k > 0
	 * each normal is first replaced by the renormalised sum of the normals
	 * in its (2k+1)^2 neighbourhood (range noise makes single normals of
	 * near surfaces noisy, which the cascades would see as texture). */
	static cv::Mat fromNormals(
	    const cv::Mat& normals, const cv::Mat& normalMask,
	    DetectionChannel channel, int smoothing = 0);
};

}  // namespace semnav
