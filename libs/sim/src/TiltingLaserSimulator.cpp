/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/poses/CPose3D.h>
#include <semnav/common/Error.h>
#include <semnav/scan/TiltGeometry.h>
#include <semnav/sim/TiltingLaserSimulator.h>

#include <cmath>
#include <exception>
#include <random>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace semnav
{
namespace
{
uint64_t splitMix64(uint64_t x)
{
	x += 0x9E3779B97F4A7C15ULL;
	x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
	x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
	return x ^ (x >> 31);
}

/** Seed of the noise of one scan line. */
uint64_t lineSeed(uint64_t seed, std::size_t sweep, std::size_t line)
{
	return splitMix64(
	    splitMix64(splitMix64(seed ^ 0x5157A11C0FFEEULL) ^ sweep) ^ line);
}
}  // namespace

TiltingLaserSimulator::TiltingLaserSimulator(
    const RayCaster& caster, const SensorSpec& spec, uint64_t seed,
    std::string sensorLabel)
    : m_caster(caster),
      m_spec(spec),
      m_seed(seed),
      m_sensorLabel(std::move(sensorLabel))
{
	const std::size_t nl = spec.lineCount(), nb = spec.beamCount();
	if (nl == 0 || nb == 0)
		throw Error(
		    "TiltingLaserSimulator: the sensor spec has no lines or no beams");
	if (!(spec.maxRange > 0) || !(spec.rangeNoise >= 0))
		throw Error(
		    "TiltingLaserSimulator: max range must be > 0 and range noise >= "
		    "0");
	if (caster.maxInstanceId() > 255)
		throw Error(
		    "TiltingLaserSimulator: object id " +
		    std::to_string(caster.maxInstanceId()) +
		    " does not fit in a ground-truth label image (max 255 objects)");
	for (std::size_t r = 0; r < nl; r++)
		m_thetas.push_back(spec.thetaMin + r * spec.thetaStep);
	for (std::size_t c = 0; c < nb; c++)
		m_phis.push_back(spec.phiMin + c * spec.phiStep);
	// MRPT spreads the beams symmetrically about the scanner's x axis over
	// the aperture (nb - 1) * step; the scanner's x axis is its centre.
	m_phiCenter = spec.phiMin + 0.5 * (nb - 1) * spec.phiStep;
	for (double p : m_phis)
	{
		m_cosPhi.push_back(std::cos(p - m_phiCenter));
		m_sinPhi.push_back(std::sin(p - m_phiCenter));
	}
}

SimulatedSweep TiltingLaserSimulator::simulate(
    const mrpt::math::TPose2D& robotPose, std::size_t sweepIndex,
    mrpt::Clock::time_point t0, double linePeriod) const
{
	const int nl = static_cast<int>(m_thetas.size());
	const int nb = static_cast<int>(m_phis.size());
	SimulatedSweep out;
	out.index = sweepIndex;
	out.truePose = robotPose;
	out.ascending = (sweepIndex % 2) == 0;
	out.thetas = m_thetas;
	for (double p : m_phis) out.bearings.push_back(p - m_phiCenter);
	out.lines.resize(nl);
	out.labels = cv::Mat::zeros(nl, nb, CV_16UC1);
	out.trueRanges = cv::Mat::zeros(nl, nb, CV_32FC1);

	const mrpt::poses::CPose3D robot(
	    robotPose.x, robotPose.y, 0, robotPose.phi, 0, 0);
	const float maxRange = static_cast<float>(m_spec.maxRange);
	const float aperture = static_cast<float>((nb - 1) * m_spec.phiStep);
	constexpr double ticksPerSecond =
	    static_cast<double>(mrpt::Clock::period::den) /
	    mrpt::Clock::period::num;

	int threads = m_threads;
#ifdef _OPENMP
	if (threads <= 0) threads = omp_get_max_threads();
#else
	threads = 1;
#endif
	std::exception_ptr error;

#pragma omp parallel for schedule(dynamic, 4) num_threads(threads)
	for (int i = 0; i < nl; i++)
	{
		try
		{
			const int row = out.ascending ? i : nl - 1 - i;
			const double theta = m_thetas[row];
			auto& scan = out.lines[i];
			scan.sensorLabel = m_sensorLabel;
			scan.aperture = aperture;
			scan.rightToLeft = true;
			scan.maxRange = maxRange;
			scan.stdError = static_cast<float>(m_spec.rangeNoise);
			scan.sensorPose =
			    tiltedSensorPose(m_spec.mount, theta, m_phiCenter);
			scan.timestamp =
			    t0 + mrpt::Clock::duration(static_cast<mrpt::Clock::rep>(
			             std::llround(i * linePeriod * ticksPerSecond)));
			scan.resizeScan(nb);

			const mrpt::poses::CPose3D world = robot + scan.sensorPose;
			const auto& R = world.getRotationMatrix();
			const mrpt::math::TPoint3D o(world.x(), world.y(), world.z());
			std::mt19937_64 rng(lineSeed(m_seed, sweepIndex, row));
			std::normal_distribution<double> nd(0.0, 1.0);
			auto* lab = out.labels.ptr<uint16_t>(row);
			auto* tr = out.trueRanges.ptr<float>(row);
			for (int c = 0; c < nb; c++)
			{
				const double cp = m_cosPhi[c], sp = m_sinPhi[c];
				const mrpt::math::TPoint3D d(
				    cp * R(0, 0) + sp * R(0, 1), cp * R(1, 0) + sp * R(1, 1),
				    cp * R(2, 0) + sp * R(2, 1));
				const RayHit h = m_caster.cast(o, d, m_spec.maxRange);
				// One draw per beam, hit or not, so streams stay aligned.
				const double meas = h.range + m_spec.rangeNoise * nd(rng);
				const bool valid = h.hit && meas > 0 && meas <= m_spec.maxRange;
				scan.setScanRange(
				    c, valid ? static_cast<float>(meas) : maxRange);
				scan.setScanRangeValidity(c, valid);
				if (valid)
				{
					lab[c] = static_cast<uint16_t>(
					    static_cast<unsigned>(h.label) |
					    (static_cast<unsigned>(h.instance) << 8));
					tr[c] = static_cast<float>(h.range);
				}
			}
		}
		catch (...)
		{
#pragma omp critical(semnav_sim_error)
			if (!error) error = std::current_exception();
		}
	}
	if (error) std::rethrow_exception(error);
	return out;
}

Sweep SimulatedSweep::toSweep() const
{
	const std::size_t nl = lines.size();
	const std::size_t nb = bearings.size();
	Sweep s(nl, nb);
	s.setPhis(bearings);
	for (std::size_t r = 0; r < nl; r++)
	{
		const auto& line = lines[ascending ? r : nl - 1 - r];
		s.setRow(r, thetas[r], line.sensorPose);
		for (std::size_t c = 0; c < nb; c++)
			s.setRange(
			    r, c, line.getScanRange(c), line.getScanRangeValidity(c));
	}
	if (!lines.empty())
	{
		s.setTimestamp(lines.front().timestamp);
		s.setSensorLabel(lines.front().sensorLabel);
		s.setMaxRange(lines.front().maxRange);
	}
	s.setIndex(index);
	s.quality().ascending = ascending;
	return s;
}

}  // namespace semnav
