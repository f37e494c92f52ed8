/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/Error.h>
#include <semnav/emulation/EmulatedDiffDriveBase.h>
#include <semnav/sim/RayCaster.h>
#include <semnav/sim/SimulatedBase.h>

#include <chrono>
#include <iomanip>

namespace semnav
{
EmulatedDiffDriveBase::EmulatedDiffDriveBase(
    const Scene& scene, const mrpt::math::TPose2D& start,
    const Options& options)
    : m_scene(scene), m_options(options)
{
	m_options.robot.watchdog = options.watchdog;
	m_options.robot.timeStep = options.step;
	m_caster = std::make_unique<RayCaster>(m_scene, options.seed);
	const auto clock = mrpt::Clock::getActiveClock();
	m_base = std::make_unique<SimulatedBase>(*m_caster, m_options.robot, start);
	mrpt::Clock::setActiveClock(clock);  // wall time, see the class doc
	if (options.odometryNoise)
		m_base->setOdometryNoise(m_scene.odometry, options.seed + 7919);
	if (!options.trajectoryFile.empty())
	{
		m_trajectory.open(options.trajectoryFile);
		if (!m_trajectory)
			throw IoError("cannot write " + options.trajectoryFile);
		m_trajectory << std::setprecision(15);
	}
}

EmulatedDiffDriveBase::~EmulatedDiffDriveBase()
{
	stop();
}

void EmulatedDiffDriveBase::start()
{
	if (m_running.exchange(true)) return;
	m_thread = std::thread([this] { run(); });
}

void EmulatedDiffDriveBase::stop()
{
	if (m_running.exchange(false)) m_thread.join();
	std::lock_guard<std::mutex> lock(m_mutex);
	if (m_trajectory.is_open()) m_trajectory.close();
}

void EmulatedDiffDriveBase::command(double v, double w)
{
	std::lock_guard<std::mutex> lock(m_mutex);
	m_base->setVelocity(v, w);
	m_commands++;
}

EmulatedDiffDriveBase::State EmulatedDiffDriveBase::state() const
{
	std::lock_guard<std::mutex> lock(m_mutex);
	State s;
	s.truePose = m_base->pose();
	s.odometry = m_base->odometry();
	s.velocity = s.odometry.velocity;
	s.collisions = m_base->collisions();
	s.watchdogStops = m_base->watchdogStops();
	s.commands = m_commands;
	s.time = m_base->time();
	return s;
}

mrpt::math::TPose2D EmulatedDiffDriveBase::truePose() const
{
	std::lock_guard<std::mutex> lock(m_mutex);
	return m_base->pose();
}

void EmulatedDiffDriveBase::run()
{
	using Clock = std::chrono::steady_clock;
	const auto period = std::chrono::duration_cast<Clock::duration>(
	    std::chrono::duration<double>(m_options.step));
	auto next = Clock::now() + period;
	while (m_running)
	{
		std::this_thread::sleep_until(next);
		next += period;
		std::lock_guard<std::mutex> lock(m_mutex);
		m_base->simulate(m_options.step);
		if (m_trajectory.is_open())
		{
			const auto& p = m_base->pose();
			const auto v = m_base->odometry().velocity;
			m_trajectory
			    << std::chrono::duration<double>(
			           std::chrono::system_clock::now().time_since_epoch())
			           .count()
			    << ' ' << p.x << ' ' << p.y << ' ' << p.phi << ' ' << v.vx
			    << ' ' << v.omega << '\n';
		}
	}
}

}  // namespace semnav
