/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/common/Label.h>

#include <opencv2/core/mat.hpp>

namespace semnav
{
/** Images for people (semnav-perceive's PNGs). All take sweep-layout
 * inputs (row 0 = lowest tilt, col 0 = the robot's right) and return BGR
 * images in the *viewer's* layout: rotated by 180 degrees, so up is up and
 * the robot's left is on the left, as the paper's figures. */
namespace perception_images
{
/** Sweep layout -> viewer layout (rotation by 180 degrees). */
cv::Mat toViewerLayout(const cv::Mat& sweepLayout);

/** Fixed display colour of a label (BGR). */
cv::Vec3b labelColour(Label l);

/** Normal image (NormalImage::toBgr()) in viewer layout. */
cv::Mat normals(const cv::Mat& bgrSweepLayout);

/** Areas in random but fixed colours (area id hashed), area 0 black. */
cv::Mat segments(const cv::Mat& areaIds);

/** Labels in their colours, invalid pixels black, with a legend of the
 * labels below the image. `validMask` CV_8U may be empty. */
cv::Mat labels(const cv::Mat& labelIds, const cv::Mat& validMask);
}  // namespace perception_images

}  // namespace semnav
