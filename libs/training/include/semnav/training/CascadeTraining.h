/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/cascade/CascadeTrainer.h>
#include <semnav/cascade/HaarCascade.h>
#include <semnav/common/IniSections.h>
#include <semnav/common/Label.h>
#include <semnav/detection/CascadeDetector.h>
#include <semnav/perception/NormalImage.h>
#include <semnav/training/SampleGenerator.h>

#include <functional>
#include <map>
#include <string>
#include <vector>

namespace semnav
{
/** Training one class's cascade from simulated datasets, end to end (what
 * semnav-train-cascade runs): sweeps and ground truth of every dataset
 * directory -> normal images (NormalImage, as perception computes them) ->
 * detection images (the detector's channel) -> samples (SampleGenerator,
 * scaled by the class's upscale) -> CascadeTrainer. */
class CascadeTraining
{
public:
	/** Everything that shapes the result; one INI file (config/cascade.ini)
	 * holds [CascadeDetector] (+ class sections), [SampleGenerator],
	 * [CascadeTrainer] and optionally [NormalImage]. */
	struct TOptions
	{
		CascadeDetector::TOptions detector;
		SampleGenerator::TOptions samples;
		CascadeTrainer::TOptions trainer;
		/** [CascadeTrainer.<label>]: a class's changes to [CascadeTrainer]
		 * (keys absent there keep the [CascadeTrainer] values). */
		std::map<Label, CascadeTrainer::TOptions> trainerPerClass;
		/** [SampleGenerator.<label>]: a class's changes to
		 * [SampleGenerator]. */
		std::map<Label, SampleGenerator::TOptions> samplesPerClass;
		NormalImage::TOptions normals;
		/** The sample options of a class. */
		const SampleGenerator::TOptions& samplesFor(Label l) const
		{
			const auto it = samplesPerClass.find(l);
			return it == samplesPerClass.end() ? samples : it->second;
		}
		/** The trainer options of a class. */
		const CascadeTrainer::TOptions& trainerFor(Label l) const
		{
			const auto it = trainerPerClass.find(l);
			return it == trainerPerClass.end() ? trainer : it->second;
		}
		/** Throws ConfigError (unknown section or key, bad value). */
		static TOptions fromIniFile(const std::string& path);
		/** The sections of config/cascade.ini bound to these options
		 * (detector, samples, trainer, normals; for --write-config). */
		IniSections iniSections();
	};

	struct Result
	{
		HaarCascade cascade;
		CascadeTrainer::Report report;
		std::size_t sweeps = 0, views = 0, positives = 0, negativeImages = 0;
		/** The positive samples (window-sized, CV_8U). */
		std::vector<cv::Mat> positiveSamples;
		/** Wall-clock seconds: reading + normals, samples, training. */
		double secondsLoad = 0, secondsSamples = 0, secondsTraining = 0;
		double seconds() const
		{
			return secondsLoad + secondsSamples + secondsTraining;
		}
	};

	/** (step, steps, what): loading, sample generation, then one step per
	 * stage. */
	using Progress =
	    std::function<void(std::size_t, std::size_t, const std::string&)>;

	explicit CascadeTraining(const TOptions& options);

	/** The detection images (in `channel`) and ground truth of every sweep
	 * of the datasets, with `withRange` also each pixel's horizontal range
	 * and the pixels' angular step (for range_negatives). Throws IoError /
	 * RawlogError. */
	std::vector<TrainingSweep> loadSweeps(
	    const std::vector<std::string>& datasetDirs, DetectionChannel channel,
	    bool withRange = false) const;

	/** The positive samples run() makes for `label` from these datasets
	 * with this seed (window of the class's [CascadeTrainer] section). */
	std::vector<cv::Mat> positives(
	    Label label, const std::vector<std::string>& datasetDirs,
	    uint64_t seed) const;

	/** Trains `label` (which must have a class section). Throws
	 * ConfigError, IoError, RawlogError, CascadeError, Error. */
	Result run(
	    Label label, const std::vector<std::string>& datasetDirs, uint64_t seed,
	    const Progress& progress = {}) const;

	const TOptions& options() const { return m_options; }

private:
	/** The datasets' sweeps as run() trains `label` on them: the class's
	 * channel and passes (and range gates with range_negatives). */
	std::vector<TrainingSweep> trainingSweeps(
	    Label label, const std::vector<std::string>& datasetDirs) const;

	TOptions m_options;
};

}  // namespace semnav
