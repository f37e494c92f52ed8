/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/system/COutputLogger.h>
#include <semnav/localization/Localizer.h>
#include <semnav/localization/OccupancyMcl.h>
#include <semnav/localization/SemanticEvidenceMap.h>
#include <semnav/localization/SemanticExtractor.h>
#include <semnav/localization/WallExtractor.h>
#include <semnav/localization/WallMap.h>

#include <memory>
#include <string>
#include <vector>

namespace semnav
{
class Sweep;
class LabeledSweep;
class SemanticMap;

/** Mapping with localization (semnav-map --poses pf): each sweep is
 * localized against the map built so far, then inserted at that pose. The
 * first sweep goes in at its odometry pose (the initial pose).
 *
 * Methods: Walls (Localizer on the walls of the sweeps inserted so far),
 * OccupancyMcl (MRPT's stock likelihood field on the map's occupancy grid
 * with the horizontal scan line: the baseline) and Odometry. */
class MappingLocalizer : public mrpt::system::COutputLogger
{
public:
	enum class Method
	{
		Walls,
		OccupancyMcl,
		Odometry
	};

	/** All localization options; sections [WallExtractor], [WallMap],
	 * [Localizer], and for localizing in a known map [SemanticExtractor],
	 * [SemanticEvidence]. */
	struct TOptions : public mrpt::config::CLoadableOptions
	{
		void loadFromConfigFile(
		    const mrpt::config::CConfigFileBase& c,
		    const std::string& prefix) override;
		void saveToConfigFile(
		    mrpt::config::CConfigFileBase& c,
		    const std::string& prefix) const override;
		static const std::vector<std::string>& sections();

		WallExtractor::TOptions walls;
		WallMap::TOptions wallMap;
		Localizer::TOptions localizer;
		SemanticExtractor::TOptions semanticExtractor;
		SemanticEvidenceMap::TOptions semantic;
	};

	explicit MappingLocalizer(
	    const TOptions& options, Method method = Method::Walls);

	/** Localizes the sweep, inserts it into `map` at the estimated pose and
	 * returns that pose. */
	mrpt::poses::CPose2D process(
	    const Sweep& sweep, const LabeledSweep& labeled, SemanticMap& map);

	/** The last update (zero ms, converged, for the first sweep and for
	 * odometry). */
	const LocalizationUpdate& lastUpdate() const { return m_last; }
	const WallMap& wallMap() const { return m_walls; }
	const WallObservation& lastObservation() const { return m_obs; }

private:
	TOptions m_options;
	Method m_method;
	WallExtractor m_extractor;
	WallMap m_walls;
	Localizer m_localizer;
	OccupancyMcl m_stock;
	WallObservation m_obs;
	LocalizationUpdate m_last;
	bool m_started = false;
	mrpt::poses::CPose2D m_lastOdometry, m_pose;
};

}  // namespace semnav
