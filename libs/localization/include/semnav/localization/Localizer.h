/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/bayes/CParticleFilter.h>
#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/maps/COccupancyGridMap2D.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/system/COutputLogger.h>
#include <semnav/localization/SemanticEvidenceMap.h>
#include <semnav/localization/SemanticObservation.h>
#include <semnav/localization/WallMap.h>
#include <semnav/localization/WallMonteCarlo2D.h>
#include <semnav/localization/WallObservation.h>

#include <memory>
#include <string>
#include <vector>

namespace semnav
{
class SemanticMap;

/** What one particle-filter update did. */
struct LocalizationUpdate
{
	/** Pose estimate after the update (see Localizer::summarize) and the
	 * spread of all particles. */
	mrpt::poses::CPose2D pose;
	double stdXY = 0, stdYaw = 0;
	/** Covariance of all particles (x, y, yaw); its largest xy std dev (m)
	 * and that direction (rad, world frame, in (-pi/2, pi/2]). */
	mrpt::math::CMatrixDouble33 cov;
	double largestStd = 0, largestStdDirection = 0;
	/** Mapping (PredictionGuard): directions that followed the motion
	 * prediction, and the largest fraction of the predicted variance the
	 * sweep left. */
	int unconstrained = 0;
	double varianceRatio = 0;
	std::size_t particles = 0;
	double ess = 0;
	/** Wall-clock time of the update (prediction, weights, resampling),
	 * ms. */
	double ms = 0;
	/** Fraction of the observation's wall samples within 2 sigma of a map
	 * wall at the mean pose (1 when not computed). */
	double inlierFraction = 1;
	bool headingCorrected = false;
	/** Mapping (GroundBorders): the sweep's direction for that correction
	 * came from its sidewalk / grass borders, its walls giving none. */
	bool headingFromBorders = false;
	/** Spread below the convergence thresholds. */
	bool converged = false;
	/** A likelihood collapse was detected in this update (the particles
	 * were then spread over the free space again). */
	bool kidnapped = false;
};

/** Pose tracking, global localization and kidnapped-robot recovery with
 * MRPT's particle filter (mrpt::bayes::CParticleFilter on a
 * WallMonteCarlo2D) on wall landmarks, with the main-direction heading
 * correction of the paper (sec. 2.3). INI section [Localizer]. */
class Localizer : public mrpt::system::COutputLogger
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

		/** Particles of a pose-tracking start and of a global start. */
		int particles = 500;
		int globalParticles = 20000;
		/** KLD adaptive sample size (MRPT's TKLDParams). */
		bool adaptiveSampleSize = true;
		double kldBinXY = 0.1;
		double kldBinYaw = mrpt::DEG2RAD(2.0);
		double kldDelta = 0.02;
		double kldEpsilon = 0.05;
		int kldMinSamples = 200;
		int kldMaxSamples = 30000;
		/** Resampling when the effective sample size fraction drops below. */
		double essThreshold = 0.5;
		/** Gaussian motion model (CActionRobotMovement2D): std of x, y per
		 * metre (m/m), of yaw per metre (rad/m) and per radian turned, and
		 * minimum std devs (m, rad). */
		double motionXYPerMeter = 0.05;
		double motionYawPerMeter = mrpt::DEG2RAD(6.0);
		double motionYawPerRad = 0.05;
		double motionMinXY = 0.02;
		double motionMinYaw = mrpt::DEG2RAD(1.0);
		/** Spread of a pose-tracking start (m, rad). */
		double initialStdXY = 0.05;
		double initialStdYaw = mrpt::DEG2RAD(1.0);
		/** Main-direction heading correction (paper sec. 2.3). */
		bool mainDirections = true;
		double headingNoise = mrpt::DEG2RAD(0.5);
		double maxCorrection = mrpt::DEG2RAD(45.0);
		/** Scale of the summed log-likelihood: effective independent
		 * wall samples per sweep. */
		double effectivePoints = 12;
		/** The same after a global start, until the filter converges (a
		 * flatter likelihood keeps the hypotheses alive). */
		double globalEffectivePoints = 6;
		/** Converged when the spread is below these (m, rad). */
		double convergedStdXY = 0.15;
		double convergedStdYaw = mrpt::DEG2RAD(3.0);
		/** Kidnapped-robot detection (known map only): the inlier fraction
		 * at the mean pose stays below `kidnapInlierFraction` for
		 * `kidnapUpdates` updates. */
		bool kidnapDetection = true;
		double kidnapInlierFraction = 0.35;
		int kidnapUpdates = 2;
		/** Global starts spread the particles over the known map's cells
		 * seen at least once with an occupancy probability below this. */
		double freeCellThreshold = 0.45;
		/** Random seed of the filter (0 = fixed default). */
		int seed = 1;
	};

	Localizer();
	explicit Localizer(const TOptions& options);

	/** The walls to score against (owned by the caller; must outlive
	 * use). */
	void setWallMap(const WallMap* map);
	/** A known map: walls from its wall cells, free space for global
	 * starts and recovery; kidnap detection on (if configured). */
	void setKnownMap(const SemanticMap& map);
	/** setKnownMap() for the same map grown since (insertions): walls and
	 * free space updated around what changed (SemanticMap::changesSince),
	 * with the result of setKnownMap(). */
	void updateKnownMap(const SemanticMap& map);
	/** Semantic evidence to score beside the walls (owned by the caller;
	 * must outlive use; nullptr: walls only). */
	void setSemanticMap(const SemanticEvidenceMap* map) { m_semantic = map; }

	/** Pose tracking start: Gaussian around `pose`. */
	void initialize(const mrpt::poses::CPose2D& pose);
	/** Global start: `globalParticles` particles uniform over the known
	 * map's free cells, yaw uniform. Needs setKnownMap(). */
	void initializeGlobal();
	/** Several hypotheses (an ambiguous start about to drive and look):
	 * `globalParticles` particles split evenly into Gaussians of
	 * (stdXY, stdYaw) around `poses`. */
	void initializeAround(
	    const std::vector<mrpt::math::TPose2D>& poses, double stdXY,
	    double stdYaw);

	/** One step: motion by the odometry increment (robot frame), then the
	 * sweep's walls and (with setSemanticMap) its semantic evidence. An
	 * empty observation only predicts. */
	LocalizationUpdate update(
	    const mrpt::poses::CPose2D& odometryIncrement,
	    const WallObservation& obs,
	    const SemanticObservation* semantic = nullptr);

	mrpt::poses::CPose2D pose() const;
	/** Moves every particle by (dx, dy, dyaw) (world frame). */
	void translate(double dx, double dy, double dyaw);
	const WallMonteCarlo2D& pdf() const { return m_pdf; }
	const TOptions& options() const { return m_options; }
	const WallMap& knownWallMap() const { return m_knownWalls; }
	/** Times a kidnapping was detected. */
	int kidnappings() const { return m_kidnappings; }
	/** Convergence report of the last global start (initializeGlobal() or
	 * a kidnapping): scored updates until convergence (or so far), and
	 * after how many the spread first fell below the thresholds (-1: not
	 * yet converged). */
	int globalUpdates() const { return m_globalUpdates; }
	int convergedAfter() const { return m_convergedAfter; }

	/** MRPT particle-filter options built from TOptions (shared with the
	 * stock baseline). */
	static mrpt::bayes::CParticleFilter::TParticleFilterOptions pfOptions(
	    const TOptions& o);
	static mrpt::obs::CActionRobotMovement2D::TMotionModelOptions motionOptions(
	    const TOptions& o);
	static void kldOptions(const TOptions& o, mrpt::slam::TKLDParams& kld);
	/** Installs a fresh MRPT random generator seeded with `seed` (shared
	 * with the stock baseline). Not randomize(seed): that reseeds the engine
	 * but keeps the Gaussian the normal distribution has cached, so a run's
	 * result depended on the runs before it in the process. */
	static void seedRandomGenerator(int seed);
	/** Pose estimate and spread of a particle set: the weighted mean when
	 * converged, else the weighted mean around the heaviest cell of a
	 * coarse histogram (a mean between hypotheses is no pose). */
	static LocalizationUpdate summarize(
	    const mrpt::poses::CPosePDFParticles& pdf, const TOptions& o);

private:
	TOptions m_options;
	WallMonteCarlo2D m_pdf;
	mrpt::bayes::CParticleFilter m_pf;
	const WallMap* m_map = nullptr;
	const SemanticEvidenceMap* m_semantic = nullptr;
	WallMap m_knownWalls;
	/** Free space updated in `cells` of the known map. */
	void markFreeCells(const SemanticMap& map, const CellRect& cells);
	/** Centres of the known map's free cells (global starts). */
	std::vector<mrpt::math::TPoint2D> freeCells() const;
	/** The known map's free cells (1), their count, geometry and the map
	 * and version they were read from. */
	std::vector<uint8_t> m_free;
	std::size_t m_freeCount = 0;
	GridGeometry m_freeGeometry;
	const SemanticMap* m_known = nullptr;
	std::uint64_t m_knownVersion = 0;
	int m_lowInlierUpdates = 0;
	bool m_global = false;
	int m_globalUpdates = 0, m_convergedAfter = -1;
	int m_kidnappings = 0;
};

}  // namespace semnav
