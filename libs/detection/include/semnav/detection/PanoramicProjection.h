/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <utility>
#include <vector>

namespace semnav
{
/** Resamples sweep-layout images to azimuth x elevation ("panoramic")
 * coordinates, where objects keep their shape.
 *
 * A sweep pixel (row r, col c) is the beam at bearing phi(c) in the scan
 * plane tilted by theta(r) about the robot's y axis: direction (cos phi cos
 * theta, sin phi, cos phi sin theta). Those are spherical coordinates whose
 * poles lie at the robot's left and right: near phi = +-90 deg every tilt
 * line sees almost the same point, so an object beside the robot is smeared
 * over the whole height of the sweep image (a washbasin 0.5 m to the side
 * becomes a 15 x 200 pixel sliver). In azimuth az = atan2(sin phi, cos phi
 * cos theta) and elevation el = asin(cos phi sin theta) the poles are up
 * and down, and objects near the floor look as to a panoramic camera at
 * every bearing. The panoramic image has the sweep's size and angular steps
 * (az over the sweep's phi range, el over its theta range; row 0 = lowest
 * elevation, col 0 = the robot's right, as the sweep). Directions are
 * taken from the tilt axis (the few cm between axis and laser are
 * ignored: this is an image resampling, 3D stays with the points). */
class PanoramicProjection
{
public:
	PanoramicProjection() = default;
	/** Builds the maps for a sweep grid (bearings of the columns, tilts of
	 * the rows, both increasing). */
	PanoramicProjection(
	    const std::vector<double>& phis, const std::vector<double>& thetas);

	/** True when built for this grid (to reuse the maps). */
	bool sameGrid(
	    const std::vector<double>& phis,
	    const std::vector<double>& thetas) const;
	bool empty() const { return m_size.area() == 0; }
	cv::Size size() const { return m_size; }

	/** Sweep-layout image -> panoramic image (pixels without a source are
	 * 0). cv::INTER_LINEAR for images, cv::INTER_NEAREST for labels (a copy
	 * of nearestSource()'s pixels: cv::remap's nearest neighbours). */
	cv::Mat toPanoramic(const cv::Mat& sweepImage, int interpolation) const;
	/** Per panoramic pixel, the sweep pixel (row * cols + col) that
	 * cv::remap(INTER_NEAREST) with the inverse maps copies there, -1 where
	 * none (CV_32S, of the sweep's size; empty for grids of 2^24 pixels
	 * or more). */
	const cv::Mat& nearestSource() const { return m_nearest; }

	/** Panoramic position (x = col, y = row, fractional) of every sweep
	 * pixel, CV_32FC2 of the sweep's size. */
	const cv::Mat& forward() const { return m_forward; }
	/** Sweep position of every panoramic pixel (-1 where none),
	 * CV_32FC1 x and y maps as cv::remap takes them. */
	const cv::Mat& inverseX() const { return m_invX; }
	const cv::Mat& inverseY() const { return m_invY; }

	/** The sweep pixels (x = col, y = row) whose panoramic position lies in
	 * `panoramicBox`. */
	std::vector<cv::Point> sweepPixelsIn(const cv::Rect2d& panoramicBox) const;
	/** The same for `panoramicBox` into `pixels` and, of those, the ones in
	 * `inner` (which must lie within the box) into `innerPixels`, in one
	 * pass. */
	void sweepPixelsIn(
	    const cv::Rect2d& panoramicBox, const cv::Rect2d& inner,
	    std::vector<cv::Point>& pixels,
	    std::vector<cv::Point>& innerPixels) const;

private:
	std::vector<double> m_phis, m_thetas;
	cv::Size m_size;
	cv::Mat m_forward, m_invX, m_invY, m_nearest;
	/** The inverse maps in cv::remap's fixed point (cv::convertMaps,
	 * CV_16SC2 + CV_16UC1), which cv::remap otherwise derives per call. */
	cv::Mat m_fixedXY, m_fixedA;
	/** Per kBlock x kBlock block of panoramic pixels, the bounds (x0, y0,
	 * x1, y1) of their sweep positions (x1 < x0: none). */
	static constexpr int kBlock = 8;
	cv::Mat m_blockBounds;
	/** Per sweep row, whether its panoramic x never decreases along it
	 * (then the row's pixels in a box are one run of columns). */
	std::vector<uint8_t> m_rowMonotonic;
	/** The sweep region holding the sources of `panoramicBox`'s pixels
	 * (empty: none). */
	cv::Rect sourceRegion(const cv::Rect2d& panoramicBox) const;
	/** The columns [first, last) of sweep row `r` in `src` whose panoramic
	 * x lies in the box's (all of src's columns when the row is not
	 * monotonic). */
	std::pair<int, int> columnsIn(
	    int r, const cv::Rect& src, const cv::Rect2d& box) const;
};

}  // namespace semnav
