/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/cascade/HaarFeature.h>

#include <opencv2/core/types.hpp>
#include <string>
#include <vector>

namespace semnav
{
/** A boosted cascade of Haar-feature decision stumps (OpenCV's "BOOST" stage
 * type, "HAAR" feature type, trees of depth 1): what semnav's trainer
 * produces, what CascadeXml reads and writes and what CascadeEvaluator and
 * cv::CascadeClassifier run. */
class HaarCascade
{
public:
	/** value < threshold ? left : right, value = the feature's sum times
	 * the window's variance normalisation factor. */
	struct Stump
	{
		int featureIdx = 0;
		float threshold = 0;
		float left = 0, right = 0;
	};
	struct Stage
	{
		/** As written in the XML; a window passes when its stage sum is >=
		 * threshold - 1e-5 (OpenCV's THRESHOLD_EPS). */
		float threshold = 0;
		std::vector<Stump> stumps;
	};
	/** Training parameters recorded in the XML's stageParams and
	 * featureParams (informative; detection does not use them). */
	struct Params
	{
		std::string boostType = "GAB";
		double minHitRate = 0.995;
		double maxFalseAlarm = 0.5;
		double weightTrimRate = 0.95;
		int maxDepth = 1;
		int maxWeakCount = 100;
		HaarMode mode = HaarMode::All;
	};

	cv::Size windowSize{20, 20};
	std::vector<HaarFeature> features;
	std::vector<Stage> stages;
	Params params;
	/** Free text kept with the cascade (semnav writes how it was made);
	 * stored as node "semnavNote", which OpenCV ignores. */
	std::string note;

	/** Number of stumps over all stages. */
	std::size_t stumpCount() const;
	bool hasTiltedFeatures() const;
	/** A copy with only the first n stages (features kept). */
	HaarCascade firstStages(std::size_t n) const;
	/** Throws CascadeError when a stump references a missing feature or a
	 * feature leaves the window. */
	void validate() const;
	bool operator==(const HaarCascade& o) const;
};

}  // namespace semnav
