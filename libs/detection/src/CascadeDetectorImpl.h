/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once
/* CascadeDetector's state shared by its files (CascadeDetector.cpp,
 * CascadeSearch.cpp, CascadeMeasure.cpp). Internal to the detection
 * library. */

#include <semnav/cascade/CascadeEvaluator.h>
#include <semnav/detection/CascadeDetector.h>
#include <semnav/detection/ShapeVerifier.h>

#include <chrono>
#include <map>
#include <opencv2/objdetect.hpp>
#include <tuple>
#include <vector>

#include "RangeGatedSearch.h"

namespace semnav
{
namespace cascade_detector
{
using Clock = std::chrono::steady_clock;

/** A class's detection passes (TClassOptions::passes: near, far). */
constexpr int kMaxPasses = 2;

/** Index of a class's pass in the per-pass scratch. */
inline std::size_t slot(std::size_t classIndex, std::size_t pass)
{
	return classIndex * kMaxPasses + pass;
}
}  // namespace cascade_detector

struct CascadeDetector::Impl
{
	std::vector<cv::CascadeClassifier> classifiers;
	/** The same cascades for the range-gated search (range_scales), per
	 * class and pass (slot()). */
	std::vector<CascadeEvaluator> evaluators;
	std::vector<cv::Size> windows;
	/** Per class and pass (slot()): its scaled detection images by
	 * upscale, kept within one detectCandidates() call (passes may run on
	 * their own threads). */
	std::vector<
	    std::map<std::tuple<DetectionChannel, double, int, int, int>, cv::Mat>>
	    scaled;
	bool keepScaled = false;
	PanoramicProjection projection;
	/** DetectionImage::viewRotation() of the last grid. */
	cv::Mat rotation;
	std::vector<double> rotationPhis, rotationThetas;
	/** Per class. */
	std::vector<std::vector<ObjectProposal>> proposals;
	/** Elevations of the first and last row of the detection image. */
	double el0 = -M_PI / 2, el1 = M_PI / 2;
	/** Per class and pass (slot()). */
	std::vector<detail::GatedScratch> gated;
	/** Per class (empty: no shape check). */
	std::vector<ShapeVerifier> verifiers;
	bool describeShapes = false;
};

}  // namespace semnav
