/* semnav: semantic navigation from tilting-laser sweeps */
// An example robot base driver plugin (docs/hardware.md, "Base driver
// plugins"): a loopback base. Its own thread plays the motor controller: it
// enforces the watchdog and integrates the odometry of the commands it
// accepted, as wheel encoders would report it. A driver for real hardware
// sends (v, w) to the controller in step() and reads its encoders there.
//   semnav-robot --plugin libsemnav_example_base.so   ([ExampleBase] keys)
#include <mrpt/math/wrap2pi.h>
#include <semnav/common/OptionTable.h>
#include <semnav/robot/RobotBasePluginApi.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <thread>

namespace
{
using SteadyClock = std::chrono::steady_clock;
using Lock = std::lock_guard<std::mutex>;

struct Options
{
	double watchdog = 0.3, rate = 50, maxSpeed = 0.5, maxTurnRate = 1.0;
};

const semnav::OptionTable<Options>& optionTable()
{
	using O = Options;
	static const auto t =
	    semnav::OptionTable<O>()
	        .real("watchdog_s", &O::watchdog, 0.02, 10, "No command: stop.")
	        .real("rate_hz", &O::rate, 1, 1000, "Control and odometry rate.")
	        .real("max_speed_mps", &O::maxSpeed, 0, 5, "|v| is clamped.")
	        .angle("max_turn_rate_deg_s", &O::maxTurnRate, 0, 720, "|w| too.");
	return t;
}

class ExampleBase : public semnav::RobotBase
{
public:
	explicit ExampleBase(const Options& o) : m_options(o)
	{
		m_thread = std::thread([this] { run(); });
	}
	~ExampleBase() override
	{
		m_running = false;
		m_thread.join();
	}

	bool setVelocity(double v, double w) override
	{
		if (!std::isfinite(v) || !std::isfinite(w)) return false;
		Lock lock(m_mutex);
		if (m_emergency) return false;
		m_v = std::clamp(v, -m_options.maxSpeed, m_options.maxSpeed);
		m_w = std::clamp(w, -m_options.maxTurnRate, m_options.maxTurnRate);
		m_lastCommand = SteadyClock::now();
		return true;
	}
	void keepAlive() override
	{
		Lock lock(m_mutex);
		m_lastCommand = SteadyClock::now();
	}
	bool stop() override
	{
		Lock lock(m_mutex);
		m_v = m_w = 0;
		return true;
	}
	bool emergencyStop() override
	{
		Lock lock(m_mutex);
		m_emergency = true;
		m_v = m_w = 0;
		return true;
	}
	void resetEmergencyStop() override
	{
		Lock lock(m_mutex);
		m_emergency = false;
	}
	bool emergencyStopped() const override
	{
		Lock lock(m_mutex);
		return m_emergency;
	}
	Odometry odometry() const override
	{
		Lock lock(m_mutex);
		return m_odometry;
	}
	double watchdogPeriod() const override { return m_options.watchdog; }

private:
	/** One control period of dt s: the watchdog, then the motion (an arc). */
	void step(double dt)
	{
		Lock lock(m_mutex);
		const std::chrono::duration<double> silent =
		    SteadyClock::now() - m_lastCommand;
		if (silent.count() > m_options.watchdog) m_v = m_w = 0;
		auto& p = m_odometry.pose;
		const double ds = m_v * dt, dphi = m_w * dt;
		const double chord =
		    std::abs(dphi) < 1e-9 ? ds : 2 * ds / dphi * std::sin(dphi / 2);
		p.x += chord * std::cos(p.phi + dphi / 2);
		p.y += chord * std::sin(p.phi + dphi / 2);
		p.phi = mrpt::math::wrapToPi(p.phi + dphi);
		m_odometry.velocity = {m_v, 0, m_w};
		m_odometry.distance += std::abs(ds);
		m_odometry.time = mrpt::Clock::now();
	}
	void run()
	{
		const std::chrono::duration<double> period(1 / m_options.rate);
		for (auto last = SteadyClock::now(); m_running;)
		{
			std::this_thread::sleep_for(period);
			const auto now = SteadyClock::now();
			step(std::chrono::duration<double>(now - last).count());
			last = now;
		}
	}

	const Options m_options;
	mutable std::mutex m_mutex;
	double m_v = 0, m_w = 0;
	bool m_emergency = false;
	SteadyClock::time_point m_lastCommand;
	Odometry m_odometry;
	std::atomic<bool> m_running{true};
	std::thread m_thread;
};

std::unique_ptr<semnav::RobotBase> createExampleBase(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section)
{
	Options options;
	optionTable().load(options, cfg, section);  // unknown keys: ConfigError
	return std::make_unique<ExampleBase>(options);
}
}  // namespace

SEMNAV_ROBOT_BASE_PLUGIN("ExampleBase", createExampleBase)
