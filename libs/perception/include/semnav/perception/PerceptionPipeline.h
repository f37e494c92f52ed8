/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/system/COutputLogger.h>
#include <semnav/perception/LabeledSweep.h>
#include <semnav/perception/NormalImage.h>
#include <semnav/perception/RangeSegmentation.h>
#include <semnav/perception/Roughness.h>
#include <semnav/perception/RuleClassifier.h>
#include <semnav/scan/Sweep.h>

#include <string>
#include <vector>

namespace semnav
{
/** Runs the perception stages on a sweep: NormalImage -> RangeSegmentation
 * -> Roughness -> RuleClassifier, and times each of them. Buffers are kept
 * between calls, so one pipeline per thread. */
class PerceptionPipeline : public mrpt::system::COutputLogger
{
public:
	/** The stages' options, each in its own INI section:
	 * [NormalImage], [RangeSegmentation], [Roughness], [RuleClassifier]
	 * (the `section` argument of load/save is a prefix for these names,
	 * normally empty). */
	struct TOptions : public mrpt::config::CLoadableOptions
	{
		void loadFromConfigFile(
		    const mrpt::config::CConfigFileBase& c,
		    const std::string& sectionPrefix) override;
		void saveToConfigFile(
		    mrpt::config::CConfigFileBase& c,
		    const std::string& sectionPrefix) const override;

		NormalImage::TOptions normals;
		RangeSegmentation::TOptions segmentation;
		Roughness::TOptions roughness;
		RuleClassifier::TOptions classifier;
	};

	/** Section names of TOptions (without prefix). */
	static const std::vector<std::string>& sections();

	/** Wall-clock time of the stages of the last process() call, ms. */
	struct Timings
	{
		double normals = 0, segmentation = 0, roughness = 0, classification = 0,
		       total = 0;
	};

	PerceptionPipeline();
	explicit PerceptionPipeline(const TOptions& options);

	/** Processes one sweep. Never throws for bad sweep contents: an empty
	 * or all-invalid sweep gives an all-Unknown result (with a warning in
	 * the log). Pass the same `out` for every sweep to reuse its buffers
	 * (no allocation, no copy). */
	void process(const Sweep& sweep, LabeledSweep& out);
	LabeledSweep process(const Sweep& sweep);

	const Timings& lastTimings() const { return m_timings; }
	/** The stages (options, counters). Their images are handed over to the
	 * LabeledSweep by process() (buffer swap, no copy): read the results
	 * there, not here. */
	const NormalImage& normalImage() const { return m_normals; }
	const RangeSegmentation& segmentation() const { return m_segmentation; }
	const Roughness& roughness() const { return m_roughness; }
	const RuleClassifier& classifier() const { return m_classifier; }
	const TOptions& options() const { return m_options; }

private:
	TOptions m_options;
	NormalImage m_normals;
	RangeSegmentation m_segmentation;
	Roughness m_roughness;
	RuleClassifier m_classifier;
	Timings m_timings;
};

}  // namespace semnav
