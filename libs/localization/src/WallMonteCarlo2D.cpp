/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/bayes/CParticleFilterCapable.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/math/wrap2pi.h>
// PF_implementations.h (MRPT's proposal templates) names this unqualified.
namespace mrpt::slam
{
using mrpt::bayes::INVALID_LIKELIHOOD_VALUE;
}
#include <mrpt/slam/PF_implementations.h>
#include <semnav/localization/MainDirections.h>
#include <semnav/localization/SemanticEvidenceMap.h>
#include <semnav/localization/WallMap.h>
#include <semnav/localization/WallMonteCarlo2D.h>

#include <cmath>

namespace semnav::detail
{
/** KLD bin of a 2D pose whose heading is the corrected one. */
struct TCorrectedPoseBin2D
{
	int x = 0, y = 0, phi = 0;
	struct lt_operator
	{
		bool operator()(
		    const TCorrectedPoseBin2D& a, const TCorrectedPoseBin2D& b) const
		{
			if (a.x != b.x) return a.x < b.x;
			if (a.y != b.y) return a.y < b.y;
			return a.phi < b.phi;
		}
	};
};
/** The filter whose proposal is running (MRPT's bin loader is a free
 * function without it). */
thread_local const WallMonteCarlo2D* tlCurrent = nullptr;
}  // namespace semnav::detail

namespace mrpt::slam
{
template <>
void KLF_loadBinFromParticle<
    mrpt::math::TPose2D, semnav::detail::TCorrectedPoseBin2D>(
    semnav::detail::TCorrectedPoseBin2D& outBin, const TKLDParams& opts,
    const mrpt::math::TPose2D* current, const mrpt::math::TPose3D* newPose)
{
	double x = 0, y = 0, yaw = 0;
	if (newPose)
		x = newPose->x, y = newPose->y, yaw = newPose->yaw;
	else if (current)
		x = current->x, y = current->y, yaw = current->phi;
	if (semnav::detail::tlCurrent)
		yaw = semnav::detail::tlCurrent->alignedYaw(yaw);
	outBin.x = static_cast<int>(std::round(x / opts.KLD_binSize_XY));
	outBin.y = static_cast<int>(std::round(y / opts.KLD_binSize_XY));
	outBin.phi = static_cast<int>(std::round(yaw / opts.KLD_binSize_PHI));
}
}  // namespace mrpt::slam

namespace semnav
{
WallMonteCarlo2D::WallMonteCarlo2D(std::size_t particles)
    : CMonteCarloLocalization2D(particles)
{
	// Never read (our likelihood hook scores the walls); MRPT asserts it.
	options.metricMap = std::make_shared<mrpt::maps::CSimplePointsMap>();
}

void WallMonteCarlo2D::setHeadingCorrection(
    std::optional<double> mapDirection, std::optional<double> observed,
    double headingNoise, double maxCorrection)
{
	m_mapDirection = mapDirection;
	m_observedDirection = observed;
	m_headingNoise = headingNoise;
	m_maxCorrection = maxCorrection;
}

double WallMonteCarlo2D::alignedYaw(double yaw) const
{
	if (!m_mapDirection || !m_observedDirection) return yaw;
	const double d =
	    MainDirections::correction(yaw, *m_observedDirection, *m_mapDirection);
	if (std::abs(d) > m_maxCorrection) return yaw;
	return mrpt::math::wrapToPi(yaw + d);
}

double WallMonteCarlo2D::correctedYaw(double yaw) const
{
	const double a = alignedYaw(yaw);
	if (a == yaw) return yaw;
	return mrpt::math::wrapToPi(a + m_rng.drawGaussian1D(0, m_headingNoise));
}

void WallMonteCarlo2D::prediction_and_update_pfStandardProposal(
    const mrpt::obs::CActionCollection* action,
    const mrpt::obs::CSensoryFrame* observation,
    const mrpt::bayes::CParticleFilter::TParticleFilterOptions& PF_options)
{
	detail::tlCurrent = this;
	try
	{
		PF_SLAM_implementation_pfStandardProposal<detail::TCorrectedPoseBin2D>(
		    action, observation, PF_options, options.KLD_params);
	}
	catch (...)
	{
		detail::tlCurrent = nullptr;
		throw;
	}
	detail::tlCurrent = nullptr;
}

double WallMonteCarlo2D::observationLogLikelihood(
    double x, double y, double yaw) const
{
	if (!m_map || !m_obs || m_map->empty()) return 0;
	return m_map->logLikelihood(x, y, yaw, m_obs->samples);
}

double WallMonteCarlo2D::PF_SLAM_computeObservationLikelihoodForParticle(
    const mrpt::bayes::CParticleFilter::TParticleFilterOptions&, const size_t,
    const mrpt::obs::CSensoryFrame&, const mrpt::poses::CPose3D& x) const
{
	double ll = 0;
	if (m_obs && !m_obs->samples.empty())
		ll += observationLogLikelihood(x.x(), x.y(), x.yaw()) *
		      m_effectivePoints / double(m_obs->samples.size());
	if (m_semanticMap && m_semanticObs)
		ll +=
		    m_semanticMap->logLikelihood(x.x(), x.y(), x.yaw(), *m_semanticObs);
	return ll;
}

void WallMonteCarlo2D::
    PF_SLAM_implementation_custom_update_particle_with_new_pose(
        mrpt::math::TPose2D* particleData,
        const mrpt::math::TPose3D& newPose) const
{
	particleData->x = newPose.x;
	particleData->y = newPose.y;
	particleData->phi = correctedYaw(newPose.yaw);
}

void WallMonteCarlo2D::PF_SLAM_implementation_replaceByNewParticleSet(
    CParticleList& old_particles,
    const std::vector<mrpt::math::TPose3D>& newParticles,
    const std::vector<double>& newParticlesWeight,
    const std::vector<size_t>& newParticlesDerivedFromIdx) const
{
	std::vector<mrpt::math::TPose3D> corrected = newParticles;
	for (auto& p : corrected) p.yaw = correctedYaw(p.yaw);
	CMonteCarloLocalization2D::PF_SLAM_implementation_replaceByNewParticleSet(
	    old_particles, corrected, newParticlesWeight,
	    newParticlesDerivedFromIdx);
}

}  // namespace semnav
