/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/math/TPose2D.h>
#include <mrpt/poses/CPose2D.h>
#include <semnav/sim/Scene.h>

#include <cstdint>
#include <random>
#include <vector>

namespace semnav
{
/** Noisy wheel odometry for stop-and-scan motion.
 *
 * The odometry frame is the world frame at the start: the odometry pose
 * starts equal to the first true pose. For each motion between consecutive
 * true poses p0 -> p1, with true increment d = p1 (-) p0 and distance
 * s = |(d.x, d.y)|, the measured increment is
 * d + (N(0, transNoise s), N(0, transNoise s),
 *      rotBiasPerM s + N(0, rotNoisePerM s))
 * and odometry = odometry (+) measured increment. Pure rotations (s = 0)
 * are measured exactly. Deterministic for a given seed. */
class OdometrySimulator
{
public:
	OdometrySimulator(
	    const OdometrySpec& spec, const mrpt::math::TPose2D& start,
	    uint64_t seed = 0);

	/** Applies the true motion p0 -> p1; returns the new odometry pose. */
	const mrpt::poses::CPose2D& move(
	    const mrpt::math::TPose2D& p0, const mrpt::math::TPose2D& p1);

	const mrpt::poses::CPose2D& odometry() const { return m_odo; }

	/** Odometry poses along a whole trajectory (one per pose; the first
	 * equals trajectory[0]). */
	static std::vector<mrpt::poses::CPose2D> simulate(
	    const OdometrySpec& spec,
	    const std::vector<mrpt::math::TPose2D>& trajectory, uint64_t seed = 0);

private:
	OdometrySpec m_spec;
	mrpt::poses::CPose2D m_odo;
	std::mt19937_64 m_rng;
	std::normal_distribution<double> m_normal{0.0, 1.0};
};

}  // namespace semnav
