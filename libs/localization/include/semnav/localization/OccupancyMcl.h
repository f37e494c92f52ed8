/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/bayes/CParticleFilter.h>
#include <mrpt/maps/COccupancyGridMap2D.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/slam/CMonteCarloLocalization2D.h>
#include <semnav/localization/Localizer.h>

#include <memory>

namespace semnav
{
class Sweep;
class SemanticMap;

/** The baseline: MRPT's stock CMonteCarloLocalization2D with the
 * occupancy grid's likelihood-field model (Thrun), fed by the sweep's
 * horizontal scan line (the row whose tilt is nearest 0). Same particle
 * filter, motion model and KLD options as Localizer, no main directions. */
class OccupancyMcl
{
public:
	explicit OccupancyMcl(const Localizer::TOptions& options);

	/** A copy of the grid is scored (its likelihood options are set to the
	 * likelihood field: sigma `sigma` m, decimation 1). */
	void setMap(const mrpt::maps::COccupancyGridMap2D& grid);
	void initialize(const mrpt::poses::CPose2D& pose);
	LocalizationUpdate update(
	    const mrpt::poses::CPose2D& odometryIncrement,
	    const mrpt::obs::CObservation2DRangeScan& scan);
	mrpt::poses::CPose2D pose() const;

	/** The sweep's row nearest theta = 0 as a 2D scan in the robot frame
	 * (its sensorPose = the row's scanner pose, pitch forced to 0). */
	static mrpt::obs::CObservation2DRangeScan horizontalScan(
	    const Sweep& sweep);

	/** The semantic map's occupancy as an MRPT grid in MRPT's convention
	 * (cell value = probability of being free). SemanticMap::occupancyGrid()
	 * holds the occupancy probability itself, which MRPT's likelihood
	 * models and free-space sampling would read inverted. */
	static mrpt::maps::COccupancyGridMap2D mrptGrid(const SemanticMap& map);

	double sigma = 0.08;

private:
	Localizer::TOptions m_options;
	mrpt::slam::CMonteCarloLocalization2D m_pdf;
	mrpt::bayes::CParticleFilter m_pf;
};

}  // namespace semnav
