/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <semnav/scan/Sweep.h>

#include <cmath>
#include <opencv2/core/mat.hpp>
#include <string>

namespace semnav
{
namespace detail
{
struct NormalKernelArgs;
}

/** The paper's normal image (sec. 2.1): a unit normal per sweep pixel.
 *
 * For pixel (i, j) with robot-frame point p, the four diagonal neighbours
 * (i+-1, j-1), (i+-1, j+1) are considered; a neighbour p_n is rejected
 * unless eps0 <= |p - p_n| <= eps1 (0.5 cm, 30 cm). The normal is the sum
 * over pairs of accepted neighbours of the cross products of the edge
 * vectors (p_a - p) x (p_b - p), normalised and oriented toward the sensor
 * (docs/design.md). Pixels without a normal (invalid range, fewer than two
 * usable neighbours) have normalMask() == 0 and a zero normal.
 *
 * Colours follow the paper's figures (docs/design.md): R = 128 + 127 n_right,
 * G = 128 + 127 n_forward, B = 128 + 127 n_up with n_right = -n_y,
 * n_forward = n_x, n_up = n_z in the robot frame: floor (128,128,255),
 * ceiling (128,128,1), wall on the left (255,128,128), on the right
 * (1,128,128), facing the robot (128,1,128). Pixels without normal are
 * black.
 *
 * Images have the sweep's layout: rows() x cols(), row 0 = lowest tilt,
 * col 0 = the robot's right. Buffers are reused between compute() calls. */
class NormalImage
{
public:
	/** INI section [NormalImage]. */
	struct TOptions : public mrpt::config::CLoadableOptions
	{
		void loadFromConfigFile(
		    const mrpt::config::CConfigFileBase& c,
		    const std::string& section) override;
		void saveToConfigFile(
		    mrpt::config::CConfigFileBase& c,
		    const std::string& section) const override;

		/** eps0: neighbours closer than this are rejected (m);
		 * min_neighbour_distance_m. */
		double minNeighbourDistance = 0.005;
		/** eps1: neighbours farther than this are rejected (m);
		 * max_neighbour_distance_m. */
		double maxNeighbourDistance = 0.30;
		/** A pair of edge vectors closer than this angle to (anti)parallel
		 * adds nothing but noise and is skipped (rad);
		 * min_pair_angle_deg. */
		double minPairAngle = 5.0 * M_PI / 180.0;
		/** Toward the sweep's sides the beam runs almost along the tilt
		 * axis and neighbouring rows lie far closer than neighbouring
		 * columns (r cos(phi) times the tilt step). When > 1, the pixels
		 * of columns with floor(1 / |cos phi|) >= 2 take their
		 * neighbours that many rows away (at most this many, and at most
		 * to the first / last row) instead of one; 0 or 1: off (the
		 * paper's neighbours everywhere); side_row_step_max. Prototype
		 * (docs/generated-scenes-log.md, branch normals5). */
		int sideRowStepMax = 0;
	};

	NormalImage();
	explicit NormalImage(const TOptions& options);

	/** Computes points, normals and masks of `sweep`. Ranges that are NaN,
	 * infinite or <= 0 count as invalid even when flagged valid. An empty
	 * sweep gives empty images. */
	void compute(const Sweep& sweep);

	std::size_t rows() const { return static_cast<std::size_t>(m_points.rows); }
	std::size_t cols() const { return static_cast<std::size_t>(m_points.cols); }

	/** Robot-frame points, CV_32FC3 (x fwd, y left, z up); NaN where
	 * pointMask() is 0. */
	const cv::Mat& points() const { return m_points; }
	/** Ranges, CV_32F, NaN where pointMask() is 0. */
	const cv::Mat& ranges() const { return m_ranges; }
	/** CV_8U, 1 where the pixel has a valid finite range. */
	const cv::Mat& pointMask() const { return m_pointMask; }
	/** Unit normals, CV_32FC3, toward the sensor; 0 where normalMask() is
	 * 0. */
	const cv::Mat& normals() const { return m_normals; }
	/** CV_8U, 1 where the pixel has a normal. */
	const cv::Mat& normalMask() const { return m_normalMask; }
	/** The normals the rule classifier and the roughness read: those of
	 * normals() with the side columns recomputed from rows farther apart
	 * (TOptions::sideRowStepMax); the very Mats of normals() when that is
	 * off. normals() stays the paper's normals: the object detectors and
	 * their training read those (LabeledSweep::normals, swapOutputs()). */
	const cv::Mat& classifierNormals() const
	{
		return widened() ? m_sideNormals : m_normals;
	}
	/** The mask of classifierNormals(). */
	const cv::Mat& classifierNormalMask() const
	{
		return widened() ? m_sideNormalMask : m_normalMask;
	}
	/** True when classifierNormals() differ from normals() (side row
	 * steps on). */
	bool widened() const { return m_options.sideRowStepMax > 1; }
	/** Sensor position of each row in the robot frame. */
	const std::vector<cv::Vec3f>& sensorPositions() const
	{
		return m_sensorPos;
	}
	std::size_t validPoints() const { return m_validPoints; }
	/** Pixels with a normal in normals(). */
	std::size_t validNormals() const { return m_validNormals; }

	/** The colour image in OpenCV's BGR channel order (for cv::imencode),
	 * sweep layout. */
	cv::Mat toBgr() const { return toBgr(m_normals, m_normalMask); }
	/** The same for given normals (CV_32FC3) and mask (CV_8U), e.g. those
	 * kept in a LabeledSweep. */
	static cv::Mat toBgr(const cv::Mat& normals, const cv::Mat& mask);
	/** (R, G, B) of a unit normal, as in the paper's figures. */
	static cv::Vec3b rgbOf(const cv::Vec3f& n);

	/** classifierNormals() averaged over the (2k+1)^2 window, counting
	 * only neighbours with a normal and with the same `groups` id (CV_32S,
	 * may be empty: no restriction), renormalised. Pixels without their
	 * own normal stay without. out: CV_32FC3. */
	void smoothed(const cv::Mat& groups, int halfWidth, cv::Mat& out) const;

	const TOptions& options() const { return m_options; }

	/** Hands the results over without copying: swaps points, point mask,
	 * normals() and normalMask() (the paper's normals, not the
	 * classifier's) with the given Mats, whose buffers the next
	 * compute() reuses (pass the same Mats every time: no allocation). */
	void swapOutputs(
	    cv::Mat& points, cv::Mat& pointMask, cv::Mat& normals,
	    cv::Mat& normalMask);

private:
	/** classifierNormals(): a copy of the kernel's normals whose side
	 * columns are recomputed with widened row steps
	 * (TOptions::sideRowStepMax), from the points and thresholds of the
	 * kernel's arguments `a`. */
	void widenSideNormals(
	    const Sweep& sweep, const detail::NormalKernelArgs& a);

	TOptions m_options;
	cv::Mat m_points, m_ranges, m_pointMask, m_normals, m_normalMask;
	// classifierNormals() when widened().
	cv::Mat m_sideNormals, m_sideNormalMask;
	std::vector<cv::Vec3f> m_sensorPos;
	// Padded point planes and per-row normal sums (kernel buffers).
	std::vector<float> m_x, m_y, m_z, m_v, m_nx, m_ny, m_nz;
	int m_paddedCols = 0;
	std::size_t m_validPoints = 0, m_validNormals = 0;
};

}  // namespace semnav
