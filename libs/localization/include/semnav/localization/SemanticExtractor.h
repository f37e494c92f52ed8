/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <semnav/localization/SemanticObservation.h>

namespace semnav
{
class LabeledSweep;

/** The semantic evidence of a labelled sweep (SemanticObservation): its
 * labelled pixels projected on the floor plane and thinned to one point per
 * cell and label, and its detections' centroids. Walls and ceiling are left
 * out (the wall landmarks score walls).
 *
 * Options: INI section [SemanticExtractor] (config/localization.ini). */
class SemanticExtractor
{
public:
	struct TOptions : public mrpt::config::CLoadableOptions
	{
		void loadFromConfigFile(
		    const mrpt::config::CConfigFileBase& c,
		    const std::string& section) override;
		void saveToConfigFile(
		    mrpt::config::CConfigFileBase& c,
		    const std::string& section) const override;

		/** cell_m: one point per label and cell of this size. */
		double cell = 0.2;
		/** max_range_m: farther pixels are left out. */
		double maxRange = 6.0;
		/** max_samples_per_label: at most this many points of one label
		 * (evenly chosen). */
		int maxSamplesPerLabel = 60;
	};

	SemanticExtractor() = default;
	explicit SemanticExtractor(const TOptions& o) : m_options(o) {}

	SemanticObservation extract(const LabeledSweep& sweep) const;
	const TOptions& options() const { return m_options; }

	/** Labels scored as class points: those with object instances. */
	static bool isClassLabel(Label l);
	/** Labels scored as ground points: floor, sidewalk, grass, obstacle. */
	static bool isGroundLabel(Label l);

private:
	TOptions m_options;
};

}  // namespace semnav
