/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

namespace semnav
{
/** Which 8-bit image of the normal image the cascades see. The paper uses
 * the grey-scale version of the RGB normal image (sec. 2.2.2); the single
 * channels are R = 128 + 127 n_right, G = 128 + 127 n_forward, B = 128 +
 * 127 n_up (docs/design.md). View is the grey image of the normals turned by
 * each pixel's azimuth, so that "forward" is the line of sight: an object
 * then looks the same at every bearing (in the robot frame a wastebasket to
 * the left and one ahead have different colours). Pixels without a normal
 * are 0 in every choice. */
enum class DetectionChannel
{
	Grey,
	Red,
	Green,
	Blue,
	View
};

/** "grey", "red", "green", "blue", "view". */
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
	 * near surfaces noisy, which the cascades would see as texture).
	 * View needs the sweep's bearings `phis` (one per column) and tilts
	 * `thetas` (one per row); the other channels ignore them. */
	static cv::Mat fromNormals(
	    const cv::Mat& normals, const cv::Mat& normalMask,
	    DetectionChannel channel, int smoothing = 0,
	    const std::vector<double>& phis = {},
	    const std::vector<double>& thetas = {});

	/** The first step of fromNormals(): the normals averaged over
	 * (2k+1)^2 and renormalised (`normals` itself when k = 0). Shared by
	 * the channels of one sweep. */
	static cv::Mat smoothNormals(
	    const cv::Mat& normals, const cv::Mat& normalMask, int smoothing);
	/** The view channel's turn of every pixel: CV_32FC2 (cos, sin of the
	 * azimuth of its line of sight), for a sweep grid; computed once per
	 * grid. */
	static cv::Mat viewRotation(
	    const std::vector<double>& phis, const std::vector<double>& thetas);
	/** The second step: the channel of (smoothed) normals; `rotation`
	 * (viewRotation()) is needed for View only. fromNormals() gives the
	 * same bytes. */
	static cv::Mat fromSmoothedNormals(
	    const cv::Mat& smoothed, const cv::Mat& normalMask,
	    DetectionChannel channel, const cv::Mat& rotation = cv::Mat());
};

}  // namespace semnav
