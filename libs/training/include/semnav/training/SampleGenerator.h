/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <semnav/cascade/NegativeImage.h>
#include <semnav/cascade/RangeGate.h>
#include <semnav/common/Label.h>
#include <semnav/detection/DetectionPass.h>

#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

namespace semnav
{
/** A sweep prepared for training: its detection image (as the detector
 * makes it, before any upscaling), its ground-truth label image (CV_16U,
 * same geometry) and the detection passes of the class (empty: one pass
 * over the whole image at scale 1). */
struct TrainingSweep
{
	cv::Mat image;
	cv::Mat groundTruth;
	std::vector<DetectionPass> passes;
	/** Elevations (rad) of the first and last image row. */
	double elevation0 = 0, elevation1 = 0;
	/** Optional (empty: every window is a negative): horizontal range of
	 * each image pixel (CV_32F, 0 = none) and the class's range gate for
	 * the image at scale 1 (perSide = 1.15 / step); the negatives of each
	 * pass are then the windows the gate lets through (the detector's
	 * range_scales). */
	cv::Mat range;
	RangeGate gate;
	/** Angle between neighbouring image pixels (rad). */
	double step = 0;
};

/** Training samples for one class as in the paper (sec. 2.2.2), the
 * equivalent of opencv_createsamples:
 *
 * - positives: each visible instance of the class (at least
 *   `minObjectPixels` pixels) is cropped from the detection image with its
 *   instance mask from the ground truth (the background is transparent),
 *   its intensity is shifted at random, it is rotated about x, y and z by
 *   random angles (a perspective warp of the crop plane), pasted onto a
 *   random background window from the sweeps (away from any instance of
 *   the class), and the square around it (plus a margin, jittered) is
 *   scaled as the detector scales it (by the upscale of the detection pass
 *   that searches objects of its size, then to the window); instances are
 *   used in turn until `positives` samples exist;
 * - negatives: every detection pass's band of every sweep, scaled as the
 *   detector scales it, searched at the pass's scales, with the boxes of
 *   every instance of the class excluded; sweeps without the object are
 *   negatives entirely. */
class SampleGenerator
{
public:
	/** INI section [SampleGenerator]. */
	struct TOptions : public mrpt::config::CLoadableOptions
	{
		void loadFromConfigFile(
		    const mrpt::config::CConfigFileBase& c,
		    const std::string& section) override;
		void saveToConfigFile(
		    mrpt::config::CConfigFileBase& c,
		    const std::string& section) const override;
		static const std::vector<std::string>& knownKeys();

		/** positives: number of positive samples. */
		int positives = 1000;
		/** min_object_pixels: instances with fewer visible pixels are not
		 * cropped. */
		int minObjectPixels = 150;
		/** margin: the window side is (1 + margin) times the larger side of
		 * the instance's box. */
		double margin = 0.15;
		/** max_x_angle_deg, max_y_angle_deg, max_z_angle_deg: rotation
		 * ranges (+-) of the perspective warp (stored in rad). */
		double maxAngleX = 15.0 * M_PI / 180.0;
		double maxAngleY = 25.0 * M_PI / 180.0;
		double maxAngleZ = 8.0 * M_PI / 180.0;
		/** max_intensity_dev: object intensity shifted by up to +- this. */
		double maxIntensityDev = 20;
		/** jitter: window centre and size varied by up to +- this fraction
		 * of the side. */
		double jitter = 0.06;
		/** background_scale: background windows are scaled by a factor in
		 * [1/s, s]. */
		double backgroundScale = 1.3;
		/** own_background_fraction: fraction of positives that keep their
		 * real surroundings instead of a random background (0 = the
		 * paper's method). */
		double ownBackgroundFraction = 0.0;
		/** range_negatives: negatives only from the windows the
		 * detector's range gate lets through (TrainingSweep::range and
		 * gate, CascadeDetector range_scales), not every window. */
		bool rangeNegatives = false;
	};

	struct Result
	{
		std::vector<cv::Mat> positives;
		std::vector<NegativeImage> negatives;
		/** Instances cropped, sweeps holding none of the class. */
		std::size_t views = 0, sweepsWithoutObject = 0;
	};

	SampleGenerator();
	explicit SampleGenerator(const TOptions& options);

	/** Throws Error when no sweep shows an instance of `label` with enough
	 * pixels. The result depends only on the inputs and the seed. */
	Result generate(
	    const std::vector<TrainingSweep>& sweeps, Label label, cv::Size window,
	    uint64_t seed) const;

	/** One positive from one instance (exposed for tests): `angles` (rad)
	 * about x, y, z; `intensity` added to the object pixels; `background`
	 * (CV_8U, any size, scaled to fit) behind it. */
	cv::Mat makePositive(
	    const cv::Mat& image, const cv::Mat& objectMask, const cv::Rect& box,
	    const cv::Vec3d& angles, double intensity, const cv::Mat& background,
	    cv::Size window, double upscale, double shiftX = 0, double shiftY = 0,
	    double sizeFactor = 1) const;

	const TOptions& options() const { return m_options; }

private:
	/** Negatives: the sweeps' passes as the detector sees them, the
	 * class's boxes (`exclude`, per sweep) excluded. */
	std::vector<NegativeImage> negativeImages(
	    const std::vector<TrainingSweep>& sweeps,
	    const std::vector<std::vector<cv::Rect>>& exclude,
	    cv::Size window) const;
	TOptions m_options;
};

}  // namespace semnav
