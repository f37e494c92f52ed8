/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <semnav/perception/NormalImage.h>

#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

namespace semnav
{
/** The paper's roughness (sec. 2.2.1).
 *
 * R(i,j) = mean over the pixels (k,l) != (i,j) of the (2w+1)^2 window that
 * have a normal of n(i,j) . n(k,l) (docs/design.md: the mean dot product, flat
 * = 1; the paper's (w^2-1)^-1 factor is a typo). Then each area A is divided
 * into squares A' of w' x w' pixels (a fixed grid over the image, cut by
 * the area's border) and R-bar(A') = mean R over the pixels of A in A'.
 *
 * Option smooth_normals computes R on normals averaged over a
 * (2k+1)^2 window first: the paper's 4-neighbour normals carry the sensor's
 * range noise, which at 5 mm lowers R of a flat surface (see the tests and
 * docs/perception.md for the measured effect). */
class Roughness
{
public:
	/** INI section [Roughness]. */
	struct TOptions : public mrpt::config::CLoadableOptions
	{
		void loadFromConfigFile(
		    const mrpt::config::CConfigFileBase& c,
		    const std::string& section) override;
		void saveToConfigFile(
		    mrpt::config::CConfigFileBase& c,
		    const std::string& section) const override;

		/** w: window half-width of R; window_half_width_px. */
		int windowHalfWidth = 2;
		/** w': square width of R-bar; square_width_px. */
		int squareWidth = 5;
		/** A square's R-bar needs at least this many pixels with R;
		 * min_square_px. */
		int minSquarePixels = 3;
		/** Compute R on smoothed normals; smooth_normals. */
		bool smoothNormals = false;
		/** Half-width of that smoothing; smoothing_half_width_px. */
		int smoothingHalfWidth = 1;
	};

	Roughness();
	explicit Roughness(const TOptions& options);

	/** R per pixel and R-bar per square of each area (areaIds CV_32S;
	 * area 0 gets no R-bar, as the paper leaves it out), on
	 * normals.classifierNormals(). */
	void compute(const NormalImage& normals, const cv::Mat& areaIds);

	/** R, CV_32F, NaN where undefined (no normal or no neighbour with
	 * one). */
	const cv::Mat& r() const { return m_r; }
	/** R-bar of each pixel's (square, area), CV_32F, NaN where undefined. */
	const cv::Mat& rBar() const { return m_rBar; }

	/** R-bar per w x w square of each group: out(p) = mean of the finite
	 * values of `r` over the pixels of p's square with p's group id
	 * (groups CV_32S; ids <= 0 are left out and get NaN), NaN when fewer
	 * than minPixels values. */
	static void squareMeans(
	    const cv::Mat& r, const cv::Mat& groups, int w, int minPixels,
	    cv::Mat& out);

	const TOptions& options() const { return m_options; }

	/** Hands R and R-bar over without copying (swap; see
	 * NormalImage::swapOutputs()). */
	void swapOutputs(cv::Mat& r, cv::Mat& rBar)
	{
		cv::swap(m_r, r);
		cv::swap(m_rBar, rBar);
	}

private:
	TOptions m_options;
	cv::Mat m_r, m_rBar, m_n, m_mask, m_sumM, m_smooth;
	std::vector<float> m_tmp, m_rowSum;
};

}  // namespace semnav
