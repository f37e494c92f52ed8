/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/core/bits_math.h>
#include <semnav/localization/MainDirections.h>
#include <semnav/localization/WallObservation.h>

#include <string>

namespace semnav
{
class LabeledSweep;

/** Walls of a LabeledSweep as 2D segments in the robot frame: every region
 * labelled wall whose mean normal is horizontal gets a total-least-squares
 * line through its points (x, y), endpoints at the quantiles of the points
 * along the line, residual and fit uncertainty. Also samples points along
 * the segments (the likelihood's input) and the sweep's dominant direction.
 * INI section [WallExtractor]. */
class WallExtractor
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

		/** Regions with fewer points are skipped. */
		int minPoints = 60;
		/** Segments shorter than this are dropped (m). */
		double minLength = 0.4;
		/** Segments whose points spread more around the line are not one
		 * plane and are dropped (m). */
		double maxResidual = 0.05;
		/** |normal z| above this is not a vertical surface. */
		double maxNormalZ = 0.3;
		/** Endpoints at this quantile of the points along the line and
		 * 1 - it (robust to stray points). */
		double endpointQuantile = 0.01;
		/** Spacing of the likelihood samples along segments (m). */
		double sampleSpacing = 0.15;
		/** At most this many samples per sweep (the spacing grows). */
		int maxSamples = 60;
		/** Main direction: inlier tolerance (rad), minimum inlier length
		 * (m) and fraction of the wall length. */
		MainDirections::TEstimateOptions directions;
	};

	WallExtractor() = default;
	explicit WallExtractor(const TOptions& o) : m_options(o) {}

	WallObservation extract(const LabeledSweep& sweep) const;
	/** Fills samples and dominantDirection from segments. */
	void finish(WallObservation& obs) const;

	const TOptions& options() const { return m_options; }

private:
	TOptions m_options;
};

}  // namespace semnav
