/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/random/RandomGenerators.h>
#include <mrpt/slam/CMonteCarloLocalization2D.h>
#include <semnav/localization/SemanticObservation.h>
#include <semnav/localization/WallObservation.h>

#include <optional>

namespace semnav
{
class WallMap;
class SemanticEvidenceMap;

/** MRPT's CMonteCarloLocalization2D scoring wall observations against a
 * WallMap, with the paper's main-direction heading correction in the
 * particle propagation.
 *
 * MRPT does the rest: motion sampling from the CActionRobotMovement2D,
 * KLD adaptive sample size, weight normalisation and resampling
 * (mrpt::bayes::CParticleFilter::executeOn). Two hooks are overridden:
 * - PF_SLAM_computeObservationLikelihoodForParticle: the sum of the wall
 *   map's log-likelihood field at the observation's samples, scaled by
 *   effectivePoints / samples (the samples are correlated), plus, when
 *   set, the semantic evidence (SemanticEvidenceMap) of the sweep;
 * - the new-pose hooks of the fixed and adaptive (KLD) proposals: each
 *   propagated heading is moved by MainDirections::correction() so that the
 *   sweep's dominant wall direction lines up with the map's, plus Gaussian
 *   noise of `headingNoise`; this bounds the heading error;
 * - prediction_and_update_pfStandardProposal: runs MRPT's own template
 *   (PF_SLAM_implementation_pfStandardProposal) with a bin type whose KLD
 *   bins use the corrected heading, so KLD sizes the set for the corrected
 *   spread.
 *
 * The observation is set with setObservation() before executeOn() (the
 * CSensoryFrame handed to MRPT is not read); `options.metricMap` holds an
 * empty points map only because MRPT asserts that one is set. */
class WallMonteCarlo2D : public mrpt::slam::CMonteCarloLocalization2D
{
public:
	explicit WallMonteCarlo2D(std::size_t particles = 1);

	/** The map to score against (kept by pointer: it must outlive use). */
	void setWallMap(const WallMap* map) { m_map = map; }
	void setObservation(const WallObservation* obs) { m_obs = obs; }
	/** Semantic evidence scored beside the walls (both kept by pointer;
	 * nullptr: walls only). */
	void setSemantic(
	    const SemanticEvidenceMap* map, const SemanticObservation* obs)
	{
		m_semanticMap = map;
		m_semanticObs = obs;
	}
	/** Heading correction for the next propagation: the map's and the
	 * sweep's dominant directions (rad), or nullopt for none. */
	void setHeadingCorrection(
	    std::optional<double> mapDirection, std::optional<double> observed,
	    double headingNoise, double maxCorrection);
	/** Scale of the summed log-likelihood: effective independent samples. */
	void setEffectivePoints(double n) { m_effectivePoints = n; }
	void seed(uint32_t s) { m_rng.randomize(s); }

	/** Raw log-likelihood (before scaling) of the observation at a pose. */
	double observationLogLikelihood(double x, double y, double yaw) const;

	/** yaw + the heading correction, without noise (yaw itself when no
	 * correction is set or it exceeds the maximum). */
	double alignedYaw(double yaw) const;

	// ---- MRPT PF hooks ----------------------------------------------------
	/** MRPT's standard proposal (motion sampling, KLD, weights), with KLD
	 * bins counted on the corrected headings. */
	void prediction_and_update_pfStandardProposal(
	    const mrpt::obs::CActionCollection* action,
	    const mrpt::obs::CSensoryFrame* observation,
	    const mrpt::bayes::CParticleFilter::TParticleFilterOptions& PF_options)
	    override;
	double PF_SLAM_computeObservationLikelihoodForParticle(
	    const mrpt::bayes::CParticleFilter::TParticleFilterOptions& PF_options,
	    const size_t particleIndexForMap,
	    const mrpt::obs::CSensoryFrame& observation,
	    const mrpt::poses::CPose3D& x) const override;
	void PF_SLAM_implementation_custom_update_particle_with_new_pose(
	    mrpt::math::TPose2D* particleData,
	    const mrpt::math::TPose3D& newPose) const override;
	void PF_SLAM_implementation_replaceByNewParticleSet(
	    CParticleList& old_particles,
	    const std::vector<mrpt::math::TPose3D>& newParticles,
	    const std::vector<double>& newParticlesWeight,
	    const std::vector<size_t>& newParticlesDerivedFromIdx) const override;

private:
	double correctedYaw(double yaw) const;

	const WallMap* m_map = nullptr;
	const WallObservation* m_obs = nullptr;
	const SemanticEvidenceMap* m_semanticMap = nullptr;
	const SemanticObservation* m_semanticObs = nullptr;
	std::optional<double> m_mapDirection, m_observedDirection;
	double m_headingNoise = 0, m_maxCorrection = M_PI / 4;
	double m_effectivePoints = 10;
	mutable mrpt::random::CRandomGenerator m_rng;
};

}  // namespace semnav
