/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/system/COutputLogger.h>
#include <semnav/cascade/HaarCascade.h>
#include <semnav/cascade/NegativeImage.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace semnav
{
/** Trains a Viola-Jones boosted cascade of Haar-feature stumps, the
 * equivalent of opencv_traincascade -stageType BOOST -featureType HAAR
 * -bt GAB -maxDepth 1 (sec. 2.2.2 of the paper; Viola and Jones 2001,
 * Lienhart and Maydt 2002).
 *
 * Per stage: the positives still accepted by the stages so far and
 * `negativesPerStage` negative windows drawn at random among all those the
 * cascade so far still accepts (bootstrapping: every window of every
 * pyramid level of the negative images that detectMultiScale would
 * evaluate is tried); Gentle AdaBoost on regression stumps, with weight
 * trimming, over the whole feature pool of `mode` (features binned per stage
 * into at most `featureBins` quantile bins; thresholds are sample values, so
 * training and detection compare the same floats); weak classifiers are added
 * until the stage threshold that keeps `minHitRate` of the positives lets at
 * most `maxFalseAlarm` of the negatives through (or `maxWeakCount`). Training
 * stops after `numStages` stages, when the cascade's acceptance ratio on
 * negative windows reaches `targetFalseAlarm`, or when no more accepted
 * negative windows can be found.
 *
 * Feature values, stage sums and thresholds are computed exactly as the
 * detector computes them (CascadeEvaluator, cv::CascadeClassifier), so the
 * per-stage hit rate measured in training holds in detection. Uses all
 * cores (OpenMP) for feature evaluation, binning, split search and negative
 * mining; the result depends only on the inputs and the seed, not on the
 * number of threads.
 *
 * The library does not print: progress goes to the callback and to the
 * COutputLogger (console output off by default). */
class CascadeTrainer : public mrpt::system::COutputLogger
{
public:
	/** INI section [CascadeTrainer]. */
	struct TOptions : public mrpt::config::CLoadableOptions
	{
		void loadFromConfigFile(
		    const mrpt::config::CConfigFileBase& c,
		    const std::string& section) override;
		void saveToConfigFile(
		    mrpt::config::CConfigFileBase& c,
		    const std::string& section) const override;
		static const std::vector<std::string>& knownKeys();

		/** window_width, window_height: training window (pixels). */
		int windowWidth = 20, windowHeight = 20;
		/** feature_mode: BASIC, CORE or ALL (ALL = with the 45-degree
		 * features). */
		HaarMode mode = HaarMode::All;
		/** num_stages: maximum number of stages. */
		int numStages = 20;
		/** min_hit_rate: per stage, fraction of its positives kept. */
		double minHitRate = 0.995;
		/** calibration_fraction: this fraction of the positives (a seeded
		 * draw) is not boosted on but sets the stage thresholds: each
		 * stage keeps min_hit_rate of these (still accepted) positives as
		 * well as of the boosted ones, so that its hit rate holds on
		 * positives it has not fitted. 0 = none (every positive is
		 * boosted on). */
		double calibrationFraction = 0;
		/** max_false_alarm: per stage, maximum fraction of its negatives
		 * accepted. */
		double maxFalseAlarm = 0.5;
		/** target_false_alarm: stop when the cascade accepts at most this
		 * fraction of negative windows (0 = max_false_alarm^num_stages). */
		double targetFalseAlarm = 0;
		/** max_weak_count: maximum stumps per stage. */
		int maxWeakCount = 100;
		/** weight_trim_rate: fraction of the weight mass the stumps are
		 * fitted on (1 = no trimming). */
		double weightTrimRate = 0.95;
		/** negatives_per_stage: negative windows per stage. */
		int negativesPerStage = 2000;
		/** feature_bins: quantile bins per feature and stage (2..256). */
		int featureBins = 256;
		/** feature_fraction: fraction of the feature pool drawn (seeded) per
		 * stage; 1 = all. */
		double featureFraction = 1.0;
		/** round_feature_fraction: fraction of the stage's features
		 * (seeded draw) tried for each stump; 1 = all. */
		double roundFeatureFraction = 1.0;
		/** negative_scale_factor: pyramid step when drawing negative
		 * windows (as detectMultiScale's scaleFactor). */
		double negativeScaleFactor = 1.1;
		/** negative_max_iou: a window whose IoU with an excluded box is
		 * above this is not a negative. */
		double negativeMaxIou = 0.25;
		/** min_negatives: stop when fewer negative windows are accepted. */
		int minNegatives = 100;
		/** threads: OpenMP threads, 0 = all cores. Results do not depend
		 * on it. */
		int threads = 0;
	};

	/** What happened in one stage. */
	struct StageReport
	{
		std::size_t positives = 0, negatives = 0;
		std::size_t weakCount = 0;
		float threshold = 0;
		/** On the stage's own training samples. */
		double hitRate = 0, falseAlarm = 0;
		/** Hit rate on the calibration positives still in (0 without). */
		double calibrationHitRate = 0;
		/** Calibration positives still in at the stage's start. */
		std::size_t calibrationPositives = 0;
		/** Accepted / tried negative windows when the stage's negatives
		 * were drawn (the cascade so far). */
		double acceptanceRatio = 0;
		/** Negative windows tried then (all windows of all pyramid levels
		 * that are not excluded and pass the images' range gates). */
		std::size_t negativeWindows = 0;
		/** Wall-clock seconds: the whole stage, drawing negatives, binning
		 * feature values, boosting. */
		double seconds = 0, secondsNegatives = 0, secondsBinning = 0,
		       secondsBoosting = 0;
		/** Indices (into the positives given to train()) of the stage's
		 * positives. */
		std::vector<int> positiveIndices;
	};
	struct Report
	{
		std::vector<StageReport> stages;
		/** Positives given, and those dropped because OpenCV's detector
		 * skips windows with grey-level standard deviation <= 10. */
		std::size_t positivesGiven = 0, positivesLowContrast = 0;
		std::size_t featurePool = 0;
		/** Acceptance ratio of the final cascade on negative windows (from
		 * the last bootstrapping), and why training stopped. */
		double finalAcceptanceRatio = 1;
		std::string stopReason;
		double seconds = 0;
	};

	/** (stages done, stages at most, one-line status). */
	using Progress =
	    std::function<void(std::size_t, std::size_t, const std::string&)>;

	CascadeTrainer();
	explicit CascadeTrainer(const TOptions& options);

	/** Trains on `positives` (CV_8UC1 windows of the window size) and
	 * windows of `negatives`. Throws CascadeError on unusable input (no
	 * positive, wrong size or type, no negative window). */
	HaarCascade train(
	    const std::vector<cv::Mat>& positives,
	    const std::vector<NegativeImage>& negatives, uint64_t seed,
	    const Progress& progress = {});

	const Report& report() const { return m_report; }
	const TOptions& options() const { return m_options; }

private:
	TOptions m_options;
	Report m_report;
};

}  // namespace semnav
