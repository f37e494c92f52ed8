/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/math/wrap2pi.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/random/RandomGenerators.h>
#include <semnav/common/Error.h>
#include <semnav/localization/OccupancyMcl.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/scan/Sweep.h>

#include <chrono>
#include <cmath>

namespace semnav
{
OccupancyMcl::OccupancyMcl(const Localizer::TOptions& options)
    : m_options(options)
{
	m_pf.m_options = Localizer::pfOptions(m_options);
	Localizer::kldOptions(m_options, m_pdf.options.KLD_params);
	Localizer::seedRandomGenerator(m_options.seed);
}

void OccupancyMcl::setMap(const mrpt::maps::COccupancyGridMap2D& grid)
{
	auto g = std::make_shared<mrpt::maps::COccupancyGridMap2D>(grid);
	g->likelihoodOptions.likelihoodMethod =
	    mrpt::maps::COccupancyGridMap2D::lmLikelihoodField_Thrun;
	g->likelihoodOptions.LF_stdHit = static_cast<float>(sigma);
	g->likelihoodOptions.enableLikelihoodCache = false;
	m_pdf.options.metricMap = g;
}

void OccupancyMcl::initialize(const mrpt::poses::CPose2D& pose)
{
	m_pdf.resetDeterministic(
	    pose.asTPose(), static_cast<std::size_t>(m_options.particles));
	auto& rng = mrpt::random::getRandomGenerator();
	for (auto& p : m_pdf.m_particles)
	{
		p.d.x += rng.drawGaussian1D(0, m_options.initialStdXY);
		p.d.y += rng.drawGaussian1D(0, m_options.initialStdXY);
		p.d.phi = mrpt::math::wrapToPi(
		    p.d.phi + rng.drawGaussian1D(0, m_options.initialStdYaw));
	}
}

LocalizationUpdate OccupancyMcl::update(
    const mrpt::poses::CPose2D& odometryIncrement,
    const mrpt::obs::CObservation2DRangeScan& scan)
{
	if (!m_pdf.options.metricMap) throw Error("OccupancyMcl: no map set");
	const auto t0 = std::chrono::steady_clock::now();
	mrpt::obs::CActionRobotMovement2D act;
	act.computeFromOdometry(
	    odometryIncrement, Localizer::motionOptions(m_options));
	mrpt::obs::CActionCollection acts;
	acts.insert(act);
	mrpt::obs::CSensoryFrame sf;
	sf.insert(std::make_shared<mrpt::obs::CObservation2DRangeScan>(scan));
	mrpt::bayes::CParticleFilter::TParticleFilterStats stats;
	m_pf.executeOn(m_pdf, &acts, &sf, &stats);
	LocalizationUpdate u = Localizer::summarize(m_pdf, m_options);
	u.ms = std::chrono::duration<double, std::milli>(
	           std::chrono::steady_clock::now() - t0)
	           .count();
	return u;
}

mrpt::maps::COccupancyGridMap2D OccupancyMcl::mrptGrid(const SemanticMap& map)
{
	mrpt::maps::COccupancyGridMap2D g = map.occupancyGrid();
	const auto& geo = map.geometry();
	for (int cy = 0; cy < geo.rows; cy++)
		for (int cx = 0; cx < geo.cols; cx++)
			g.setCell(cx, cy, static_cast<float>(1.0 - map.occupancy(cx, cy)));
	return g;
}

mrpt::poses::CPose2D OccupancyMcl::pose() const
{
	return Localizer::summarize(m_pdf, m_options).pose;
}

mrpt::obs::CObservation2DRangeScan OccupancyMcl::horizontalScan(
    const Sweep& sweep)
{
	if (sweep.empty() || sweep.cols() < 2)
		throw Error("OccupancyMcl: empty sweep");
	std::size_t best = 0;
	for (std::size_t r = 1; r < sweep.rows(); r++)
		if (std::abs(sweep.theta(r)) < std::abs(sweep.theta(best))) best = r;
	const std::size_t n = sweep.cols();
	mrpt::obs::CObservation2DRangeScan scan;
	scan.sensorLabel = "HORIZONTAL";
	scan.timestamp = sweep.timestamp();
	scan.rightToLeft = true;
	const double phi0 = sweep.phi(0), phi1 = sweep.phi(n - 1);
	scan.aperture = static_cast<float>(phi1 - phi0);
	scan.maxRange = sweep.maxRange() > 0 ? sweep.maxRange() : 80.0f;
	scan.resizeScan(n);
	for (std::size_t c = 0; c < n; c++)
	{
		scan.setScanRange(c, sweep.range(best, c));
		scan.setScanRangeValidity(c, sweep.valid(best, c));
	}
	// Level scan plane (MRPT's grid ignores tilted scans); a bearing span
	// not centred on 0 turns the sensor.
	const auto& sp = sweep.sensorPose(best);
	scan.sensorPose = mrpt::poses::CPose3D(
	    sp.x(), sp.y(), sp.z(), sp.yaw() + (phi0 + phi1) / 2, 0, 0);
	return scan;
}

}  // namespace semnav
