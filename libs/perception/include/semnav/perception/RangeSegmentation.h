/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <semnav/scan/Sweep.h>

#include <opencv2/core/mat.hpp>
#include <string>
#include <utility>
#include <vector>

namespace semnav
{
/** The paper's segmentation of the range image into areas (sec. 2.2.1).
 *
 * cv::floodFill runs on the range image (floating range: a pixel joins when
 * its range differs from an already joined neighbour's by at most
 * max_neighbour_difference_m, 5 cm) from the first unassigned pixel in
 * row-major order, starting at (0, 0). An area with more than min_area_px
 * pixels (30) gets the next number 1..n, smaller ones get 0 ("not
 * considered in any later stage" by the paper). Invalid pixels (no return,
 * NaN range) never join an area and are 0. */
class RangeSegmentation
{
public:
	/** INI section [RangeSegmentation]. */
	struct TOptions : public mrpt::config::CLoadableOptions
	{
		void loadFromConfigFile(
		    const mrpt::config::CConfigFileBase& c,
		    const std::string& section) override;
		void saveToConfigFile(
		    mrpt::config::CConfigFileBase& c,
		    const std::string& section) const override;

		/** Flood-fill neighbour range difference (m);
		 * max_neighbour_difference_m. */
		double maxNeighbourDifference = 0.05;
		/** Areas must be larger than this to be numbered; min_area_px. */
		int minAreaPixels = 30;
		/** 4 or 8; connectivity. */
		int connectivity = 4;
	};

	RangeSegmentation();
	explicit RangeSegmentation(const TOptions& options);

	/** Segments the sweep's range image. */
	void compute(const Sweep& sweep);

	/** Area id per pixel, CV_32S, 0 = no area (small or invalid). */
	const cv::Mat& areaIds() const { return m_ids; }
	/** Number of numbered areas n (ids 1..n). */
	int areaCount() const { return static_cast<int>(m_sizes.size()) - 1; }
	/** Pixels of area i (index 0: pixels in no area, invalid included). */
	const std::vector<int>& areaSizes() const { return m_sizes; }
	/** Areas of two or more pixels found (before the size test); those
	 * larger than min_area_px by cv::floodFill. */
	int fills() const { return m_fills; }
	/** Pixels with no joinable neighbour (areas of one pixel). */
	int singletons() const { return m_singletons; }

	const TOptions& options() const { return m_options; }

	/** Hands the area image over without copying (swap; see
	 * NormalImage::swapOutputs()). */
	void swapOutputs(cv::Mat& areaIds) { cv::swap(m_ids, areaIds); }

private:
	/** m_range (0 where invalid) and m_mask (1 where invalid and on its
	 * frame); m_ids -1 on valid pixels, 0 elsewhere. */
	void prepareImages(const Sweep& sweep);
	/** The area of (r, c) when it is too small to be numbered (found by a
	 * bounded search): its pixels set to id 0; false when it is larger. */
	bool setAsideSmallArea(int r, int c);
	/** Fills and numbers the area of (r, c) (id 0 when too small). */
	void fillArea(int r, int c);
	TOptions m_options;
	cv::Mat m_range, m_mask, m_ids;
	std::vector<int> m_sizes;
	int m_fills = 0, m_singletons = 0;
	std::vector<std::pair<int, int>> m_small;  ///< a small area's pixels
};

}  // namespace semnav
