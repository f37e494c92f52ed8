/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/math/wrap2pi.h>
#include <mrpt/poses/CPose2D.h>
#include <semnav/common/ConfigChecks.h>
#include <semnav/common/Error.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/nav/NavigationErrors.h>
#include <semnav/nav/SimulatedRobot.h>
#include <semnav/nav/StopAndScanLocalizer.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

namespace semnav
{
namespace
{
double elapsedMs(std::chrono::steady_clock::time_point t0)
{
	return std::chrono::duration<double, std::milli>(
	           std::chrono::steady_clock::now() - t0)
	    .count();
}

std::string fmt(const char* f, double a, double b)
{
	char buf[128];
	std::snprintf(buf, sizeof(buf), f, a, b);
	return buf;
}
}  // namespace

std::string StopAndScanLocalizer::modeName(Mode m)
{
	return m == Mode::Global ? "global" : "tracking";
}

StopAndScanLocalizer::Mode StopAndScanLocalizer::modeFromName(
    const std::string& name)
{
	if (name == "global") return Mode::Global;
	if (name == "tracking") return Mode::Tracking;
	throw Error(
	    "localization mode must be global or tracking, got '" + name + "'");
}

void StopAndScanLocalizer::TOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& c, const std::string& s)
{
	checkKnownKeys(
	    c, s,
	    {"converged_fraction", "converged_radius_m", "converged_yaw_deg",
	     "max_sweeps", "turn_deg", "turn_speed_deg_s", "line_period_s",
	     "guess_std_xy_m", "guess_std_yaw_deg", "guess_particles",
	     "rescan_distance_m", "odometry_noise", "seed"});
	convergedFraction =
	    readChecked(c, s, "converged_fraction", convergedFraction, 0.5, 1.0);
	convergedRadius =
	    readChecked(c, s, "converged_radius_m", convergedRadius, 0.01, 10);
	convergedYaw = mrpt::DEG2RAD(readChecked(
	    c, s, "converged_yaw_deg", mrpt::RAD2DEG(convergedYaw), 0.1, 180));
	maxSweeps = readCheckedInt(c, s, "max_sweeps", maxSweeps, 1, 100);
	turnAngle = mrpt::DEG2RAD(
	    readChecked(c, s, "turn_deg", mrpt::RAD2DEG(turnAngle), 1, 180));
	turnSpeed = mrpt::DEG2RAD(readChecked(
	    c, s, "turn_speed_deg_s", mrpt::RAD2DEG(turnSpeed), 1, 360));
	linePeriod = readChecked(c, s, "line_period_s", linePeriod, 0, 10);
	guessStdXY = readChecked(c, s, "guess_std_xy_m", guessStdXY, 0.001, 10);
	guessStdYaw = mrpt::DEG2RAD(readChecked(
	    c, s, "guess_std_yaw_deg", mrpt::RAD2DEG(guessStdYaw), 0.01, 180));
	guessParticles =
	    readCheckedInt(c, s, "guess_particles", guessParticles, 10, 1000000);
	rescanDistance =
	    readChecked(c, s, "rescan_distance_m", rescanDistance, 0, 1000);
	odometryNoise = readCheckedBool(c, s, "odometry_noise", odometryNoise);
	seed = readCheckedInt(c, s, "seed", seed, 0, 1 << 30);
}

void StopAndScanLocalizer::TOptions::saveToConfigFile(
    mrpt::config::CConfigFileBase& c, const std::string& s) const
{
	c.write(s, "converged_fraction", convergedFraction);
	c.write(s, "converged_radius_m", convergedRadius);
	c.write(s, "converged_yaw_deg", mrpt::RAD2DEG(convergedYaw));
	c.write(s, "max_sweeps", maxSweeps);
	c.write(s, "turn_deg", mrpt::RAD2DEG(turnAngle));
	c.write(s, "turn_speed_deg_s", mrpt::RAD2DEG(turnSpeed));
	c.write(s, "line_period_s", linePeriod);
	c.write(s, "guess_std_xy_m", guessStdXY);
	c.write(s, "guess_std_yaw_deg", mrpt::RAD2DEG(guessStdYaw));
	c.write(s, "guess_particles", guessParticles);
	c.write(s, "rescan_distance_m", rescanDistance);
	c.write(s, "odometry_noise", odometryNoise);
	c.write(s, "seed", seed);
}

StopAndScanLocalizer::StopAndScanLocalizer(
    const Scene& scene, const SemanticMap& map, const TOptions& options,
    const MappingLocalizer::TOptions& localization,
    const PerceptionPipeline::TOptions& perception)
    : mrpt::system::COutputLogger("StopAndScanLocalizer"),
      m_scene(scene),
      m_map(map),
      m_options(options),
      m_locOptions(localization),
      m_perception(perception),
      m_extractor(localization.walls)
{
	// Progress goes to the log only when asked (apps print JSON on stdout).
	setMinLoggingLevel(mrpt::system::LVL_WARN);
	m_perception.setMinLoggingLevel(mrpt::system::LVL_ERROR);
	m_localizer = std::make_unique<Localizer>(m_locOptions.localizer);
	m_localizer->setMinLoggingLevel(mrpt::system::LVL_ERROR);
	m_localizer->setKnownMap(m_map);
	if (m_localizer->knownWallMap().segments().empty())
		throw LocalizationFailedError(
		    "localization: the map has no walls to localize against");
}

StopAndScanLocalizer::~StopAndScanLocalizer() = default;

StopAndScanLocalizer::Report StopAndScanLocalizer::start(
    SimulatedRobot& robot, Mode mode,
    const std::optional<mrpt::math::TPose2D>& guess)
{
	const auto t0 = std::chrono::steady_clock::now();
	if (!m_laser || m_caster != &robot.caster())
	{
		m_caster = &robot.caster();
		m_laser = std::make_unique<TiltingLaserSimulator>(
		    *m_caster, m_scene.sensor, static_cast<uint64_t>(m_options.seed));
	}
	if (m_options.odometryNoise)
		robot.setOdometryNoise(
		    m_scene.odometry, static_cast<uint64_t>(m_options.seed) + 7919);
	m_lastOdometry = robot.odometry();

	Report rep;
	rep.mode = mode;
	if (mode == Mode::Global)
		m_localizer->initializeGlobal();
	else
	{
		if (!guess)
			throw LocalizationFailedError(
			    "localization: tracking needs a start guess");
		// A wider, denser cloud than an ordinary tracking start.
		auto o = m_locOptions.localizer;
		o.initialStdXY = m_options.guessStdXY;
		o.initialStdYaw = m_options.guessStdYaw;
		o.particles = m_options.guessParticles;
		m_localizer = std::make_unique<Localizer>(o);
		m_localizer->setMinLoggingLevel(mrpt::system::LVL_ERROR);
		m_localizer->setKnownMap(m_map);
		m_localizer->initialize(mrpt::poses::CPose2D(*guess));
	}

	std::size_t segments = 0;
	for (int k = 0; k < m_options.maxSweeps; k++)
	{
		if (k > 0) robot.turnInPlace(m_options.turnAngle, m_options.turnSpeed);
		const SweepRecord r = sweepAndUpdate(robot);
		rep.records.push_back(r);
		rep.sweeps++;
		segments += r.segments;
		MRPT_LOG_INFO_FMT(
		    "start sweep %d: %zu walls, spread %.3f m %.2f deg, error %.3f m "
		    "%.2f deg, weight near the estimate %.3f",
		    k + 1, r.segments, r.stdXY, mrpt::RAD2DEG(r.stdYaw), r.errorXY,
		    mrpt::RAD2DEG(r.errorYaw), r.massNear);
		if (r.converged)
		{
			rep.converged = true;
			break;
		}
	}
	const SweepRecord& last = rep.records.back();
	rep.truth = last.truePose;
	rep.estimate = last.estimate;
	rep.errorXY = last.errorXY;
	rep.errorYaw = last.errorYaw;
	rep.ms = elapsedMs(t0);
	if (!rep.converged)
		throw LocalizationFailedError(
		    "localization (" + modeName(mode) + "): not converged after " +
		    std::to_string(rep.sweeps) + " sweeps (" +
		    std::to_string(segments) + " wall segments seen; spread " +
		    fmt("%.2f m, %.1f deg)", last.stdXY, mrpt::RAD2DEG(last.stdYaw)));
	robot.setPoseEstimate(rep.estimate);
	return rep;
}

StopAndScanLocalizer::SweepRecord StopAndScanLocalizer::rescan(
    SimulatedRobot& robot)
{
	if (!m_laser)
		throw LocalizationFailedError("localization: rescan before start");
	robot.stopNow();
	const SweepRecord r = sweepAndUpdate(robot);
	robot.setPoseEstimate(r.estimate);
	MRPT_LOG_INFO_FMT(
	    "rescan: %zu walls, error %.3f m %.2f deg", r.segments, r.errorXY,
	    mrpt::RAD2DEG(r.errorYaw));
	return r;
}

StopAndScanLocalizer::SweepRecord StopAndScanLocalizer::sweepAndUpdate(
    SimulatedRobot& robot)
{
	const auto t0 = std::chrono::steady_clock::now();
	SweepRecord rec;
	rec.truePose = robot.pose();
	const SimulatedSweep sim = m_laser->simulate(
	    rec.truePose, m_sweepIndex,
	    SimulatedRobot::timestampOf(robot.simTime()), m_options.linePeriod);
	// The robot stands still while the head nods.
	const double sweepTime =
	    m_options.linePeriod * static_cast<double>(m_laser->lineCount());
	if (sweepTime > 0) robot.simulate(sweepTime);
	Sweep sweep = sim.toSweep();
	sweep.setOdometry(mrpt::poses::CPose2D(robot.odometry()));
	m_perception.process(sweep, m_labeled);
	const WallObservation obs = m_extractor.extract(m_labeled);
	const mrpt::poses::CPose2D incr = mrpt::poses::CPose2D(robot.odometry()) -
	                                  mrpt::poses::CPose2D(m_lastOdometry);
	m_lastOdometry = robot.odometry();
	m_sweepIndex++;
	const LocalizationUpdate u = m_localizer->update(incr, obs);
	rec.estimate = u.pose.asTPose();
	rec.estimate.phi = mrpt::math::wrapToPi(rec.estimate.phi);
	rec.stdXY = u.stdXY;
	rec.stdYaw = u.stdYaw;
	rec.segments = obs.segments.size();
	rec.particles = u.particles;
	rec.massNear = massNear(rec.estimate);
	rec.converged = u.converged || rec.massNear >= m_options.convergedFraction;
	rec.updateMs = u.ms;
	const mrpt::math::TPose2D now = robot.pose();
	rec.errorXY = std::hypot(rec.estimate.x - now.x, rec.estimate.y - now.y);
	rec.errorYaw = std::abs(mrpt::math::wrapToPi(rec.estimate.phi - now.phi));
	rec.ms = elapsedMs(t0);
	m_records.push_back(rec);
	return rec;
}

double StopAndScanLocalizer::massNear(const mrpt::math::TPose2D& e) const
{
	const auto& ps = m_localizer->pdf().m_particles;
	if (ps.empty()) return 0;
	double maxLog = -std::numeric_limits<double>::infinity();
	for (const auto& p : ps) maxLog = std::max(maxLog, p.log_w);
	double total = 0, near = 0;
	const double r2 = m_options.convergedRadius * m_options.convergedRadius;
	for (const auto& p : ps)
	{
		const double w = std::exp(p.log_w - maxLog);
		total += w;
		const double dx = p.d.x - e.x, dy = p.d.y - e.y;
		if (dx * dx + dy * dy <= r2 &&
		    std::abs(mrpt::math::wrapToPi(p.d.phi - e.phi)) <=
		        m_options.convergedYaw)
			near += w;
	}
	return total > 0 ? near / total : 0;
}

}  // namespace semnav
