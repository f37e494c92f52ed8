/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/system/COutputLogger.h>
#include <semnav/localization/GroundBorders.h>
#include <semnav/localization/Localizer.h>
#include <semnav/localization/ObjectFootprints.h>
#include <semnav/localization/OccupancyMcl.h>
#include <semnav/localization/PredictionGuard.h>
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
 * Methods: Walls (Localizer on the walls of the sweeps inserted so far and,
 * with the [SemanticEvidence] weights, the sweep's semantic evidence
 * against the labels and objects of the map so far, and its object
 * footprints against those of the sweeps inserted so far; then the
 * PredictionGuard: along directions the sweep did not constrain the
 * estimate follows the motion prediction; a sweep whose walls give no
 * main direction takes that of its sidewalk / grass borders,
 * GroundBorders),
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
	 * [Localizer], [SemanticExtractor], [SemanticEvidence],
	 * [ObjectFootprints], [PredictionGuard] and [GroundBorders]. */
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
		ObjectFootprints::TOptions footprints;
		PredictionGuard::TOptions guard;
		GroundBorders::TOptions borders;
	};

	explicit MappingLocalizer(
	    const TOptions& options, Method method = Method::Walls);
	MappingLocalizer(const MappingLocalizer&) = delete;
	MappingLocalizer& operator=(const MappingLocalizer&) = delete;

	/** Localizes the sweep, inserts it into `map` at the estimated pose and
	 * returns that pose. */
	mrpt::poses::CPose2D process(
	    const Sweep& sweep, const LabeledSweep& labeled, SemanticMap& map);

	/** The last update (zero ms, converged, for the first sweep and for
	 * odometry). */
	const LocalizationUpdate& lastUpdate() const { return m_last; }
	const WallMap& wallMap() const { return m_walls; }
	const WallObservation& lastObservation() const { return m_obs; }
	/** The semantic evidence scored in the last update (the part of the
	 * sweep's that the map so far can judge). */
	const SemanticObservation& lastSemantic() const { return m_semanticObs; }
	const SemanticEvidenceMap& semanticMap() const { return m_semantic; }
	/** The object footprints of the sweeps inserted so far. */
	const ObjectFootprints& footprints() const { return m_footprints; }
	/** Time of the last semantic-evidence rebuild (ms). */
	double semanticBuildMs() const { return m_semanticMs; }

private:
	LocalizationUpdate localizeWalls(
	    const mrpt::poses::CPose2D& incr, const LabeledSweep& labeled);
	void updateSemanticMap(const SemanticMap& map);

	TOptions m_options;
	Method m_method;
	WallExtractor m_extractor;
	WallMap m_walls;
	Localizer m_localizer;
	OccupancyMcl m_stock;
	SemanticExtractor m_semanticExtractor;
	SemanticEvidenceMap m_semantic;
	ObjectFootprints m_footprints;
	std::vector<ObjectFootprints::Footprint> m_sweepFootprints;
	PredictionGuard m_guard;
	GroundBorders m_borders;
	/** The sweep's ground borders' direction (robot frame), when its walls
	 * give none. */
	std::optional<double> m_borderDirection;
	WallObservation m_obs;
	SemanticObservation m_semanticObs;
	double m_semanticMs = 0;
	LocalizationUpdate m_last;
	bool m_started = false;
	mrpt::poses::CPose2D m_lastOdometry, m_pose;
};

}  // namespace semnav
