/* semnav: semantic navigation from tilting-laser sweeps */
// semnav-robot: the headless navigation app on the robot. Live sweeps from
// the tilting LMS2xx, a real robot base (ROS 1), the map growing as it
// drives, operator commands one per line on stdin, progress as JSON lines
// on stdout (human lines on stderr).
#include <mrpt/core/format.h>
#include <semnav/common/AtomicFile.h>
#include <semnav/common/CommandLine.h>
#include <semnav/common/Error.h>
#include <semnav/common/ShippedConfig.h>
#include <semnav/hwdrivers/LiveSweepSource.h>
#include <semnav/map/MapIO.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/robot/ControlClock.h>
#include <semnav/robot/LocalizedPose.h>
#include <semnav/robot/RobotBasePlugin.h>
#include <semnav/robot/SweepObstacles.h>
#include <semnav/runtime/CommandQueue.h>
#include <semnav/runtime/RobotRunRenderer.h>
#include <semnav/runtime/RobotSession.h>
#include <semnav/runtime/RobotSetup.h>
#ifdef SEMNAV_HAVE_ROS1
#include <semnav/ros1/Ros1Base.h>
#include <semnav/ros1/Ros1CommandChannel.h>
#include <semnav/ros1/Ros1Operator.h>
#endif

#include <atomic>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <functional>
#include <iostream>
#include <memory>
#include <mutex>
#include <thread>

namespace
{
std::atomic<bool> g_stop{false};
void onSignal(int)
{
	g_stop = true;
}

std::mutex g_outMutex;

/** An event as one line for people. */
std::string humanLine(const nlohmann::json& e)
{
	const std::string ev = e.value("event", "");
	const auto pose = [&](const char* key)
	{
		if (!e.contains(key) || e[key].size() != 3) return std::string();
		const auto& p = e[key];
		return mrpt::format(
		    " at (%.2f, %.2f, %.0f deg)", p[0].get<double>(),
		    p[1].get<double>(), p[2].get<double>());
	};
	if (ev == "error")
		return e.value("command", "") + ": " + e.value("error", "");
	if (ev == "sweep")
		return "sweep" + pose("estimate") +
		       (e.value("inserted", false) ? ", inserted" : ", not inserted");
	if (ev == "goal") return "goal: " + e.value("command", "");
	if (ev == "arrived" || ev == "failed")
		return ev + ": " + e.value("command", "") + pose("pose") +
		       (e.contains("reason") ? " (" + e.value("reason", "") + ")"
		                             : std::string());
	if (ev == "new_object")
		return "new object: " + e.value("label", "") + " " +
		       std::to_string(e.value("id", 0));
	if (ev == "localized") return "localized" + pose("pose");
	if (e.contains("reason")) return ev + ": " + e.value("reason", "");
	if (e.contains("error")) return ev + ": " + e.value("error", "");
	return ev;
}
/** Also publishes every event (ROS: events_topic); may be empty. */
std::function<void(const std::string&)> g_publish;
/** One JSON line on stdout (and the events topic); the human line on
 * stderr. */
void printEvent(nlohmann::json e)
{
	e["wall_time"] = std::chrono::duration<double>(
	                     std::chrono::system_clock::now().time_since_epoch())
	                     .count();
	std::lock_guard<std::mutex> lk(g_outMutex);
	const std::string line = e.dump();
	std::cout << line << std::endl;
	if (g_publish) g_publish(line);
	std::cerr << "semnav-robot: " << humanLine(e) << std::endl;
}

#ifdef SEMNAV_HAVE_ROS1
/** Options of [section] of the robot INI. */
template <class Options>
Options sectionOptions(const semnav::RobotSetup& s, const char* section)
{
	Options o;
	try
	{
		o.loadFromConfigFile(*s.ini, section);
	}
	catch (const semnav::ConfigError& e)
	{
		throw semnav::ConfigError(s.iniPath + ": " + e.what());
	}
	return o;
}
semnav::Ros1Base::TOptions rosOptions(const semnav::RobotSetup& s)
{
	return sectionOptions<semnav::Ros1Base::TOptions>(s, "Ros1Base");
}

/** Commands and events over ROS when the base is the ROS one. */
std::unique_ptr<semnav::Ros1CommandChannel> rosChannel(
    const semnav::RobotSetup& s, semnav::CommandQueue& queue)
{
	if (s.files.base != "ros1") return nullptr;
	const auto o = rosOptions(s);
	if (o.commandTopic.empty() && o.eventsTopic.empty()) return nullptr;
	auto c = std::make_unique<semnav::Ros1CommandChannel>(
	    o.nodeName, o.masterTimeout, o.commandTopic, o.eventsTopic,
	    [&queue](const std::string& line) { queue.push(line); });
	g_publish = [ch = c.get()](const std::string& l) { ch->publish(l); };
	return c;
}

/** Map, objects, path, pose and sweeps for ROS tools, and pose goals, when
 * the base is the ROS one. */
std::unique_ptr<semnav::Ros1Operator> rosOperator(
    const semnav::RobotSetup& s, semnav::CommandQueue& queue)
{
	if (s.files.base != "ros1") return nullptr;
	const auto base = rosOptions(s);
	return std::make_unique<semnav::Ros1Operator>(
	    base.nodeName, base.masterTimeout,
	    sectionOptions<semnav::Ros1Operator::TOptions>(s, "Ros1Operator"),
	    [&queue](const std::string& line) { queue.push(line); },
	    [](const std::string& command, const std::string& error) {
		    printEvent(
		        {{"event", "error"}, {"command", command}, {"error", error}});
	    });
}
#endif

std::shared_ptr<semnav::RobotBase> makeBase(
    const semnav::RobotSetup& s, semnav::RobotBasePlugin* plugin)
{
	if (plugin)
	{
		try
		{
			return plugin->create(*s.ini);
		}
		catch (const semnav::ConfigError& e)
		{
			throw semnav::ConfigError(s.iniPath + ": " + e.what());
		}
	}
#ifdef SEMNAV_HAVE_ROS1
	return std::make_shared<semnav::Ros1Base>(rosOptions(s));
#else
	throw semnav::ConfigError(
	    s.iniPath + ": base = ros1 but this build has no ROS 1");
#endif
}

/** Lines of stdin into the queue; closes it at the end of input. */
void readStdin(semnav::CommandQueue& q)
{
	for (std::string line; std::getline(std::cin, line);) q.push(line);
	q.close();
}

int runRobot(
    semnav::RobotSetup& setup, semnav::RobotBasePlugin* plugin,
    const std::string& outDir, bool readCommandsFromStdin)
{
	semnav::createDirectories(outDir);
	auto base = makeBase(setup, plugin);
	semnav::LiveSweepSource::TOptions live;
	live.loadFromConfigFile(*setup.ini, "LiveSweepSource");
	if (live.recordPath.empty()) live.recordPath = outDir + "/robot.rawlog";
	semnav::RobotBase* b = base.get();
	semnav::LiveSweepSource sweeps(
	    *setup.ini, setup.files.laserSection, live,
	    [b]
	    {
		    const auto o = b->odometry();
		    return semnav::LiveSweepSource::OdometryReading{
		        mrpt::poses::CPose2D(o.pose), o.time};
	    });
	semnav::RealTimeClock clock(setup.files.controlPeriod);
	semnav::LocalizedPose pose(*base);
	semnav::SweepObstacles obstacles(*base, setup.navigation.sweepObstacles);
	semnav::SemanticMap map(setup.navigation.map);
	if (!setup.files.mapDir.empty())
		semnav::MapIO::load(setup.resolve(setup.files.mapDir), map);
	semnav::RobotInterfaces io;
	io.base = base.get();
	io.sweeps = &sweeps;
	io.clock = &clock;
	io.pose = &pose;
	semnav::RobotSession session(
	    map, io, obstacles, setup.navigation, setup.localization,
	    setup.perception, setup.cascades, setup.session, printEvent);
	session.monitorLaser([&sweeps] { return sweeps.linesReceived(); });
	const auto save = [&]
	{
		semnav::MapIO::save(map, outDir + "/map");
		semnav::RobotRunRenderer::write(map, session, outDir + "/robot.png");
	};
	session.onSaveMap(save);
	session.setNavLogPath(outDir + "/navigation.reactivenavlog");

	semnav::CommandQueue queue;
#ifdef SEMNAV_HAVE_ROS1
	const auto channel = rosChannel(setup, queue);
	const auto rosOut = rosOperator(setup, queue);
	if (rosOut) session.addObserver(*rosOut);
#endif
	if (readCommandsFromStdin) std::thread(readStdin, std::ref(queue)).detach();
	printEvent(
	    {{"event", "started"},
	     {"map_sweeps", map.sweepsInserted()},
	     {"objects", map.instances().size()},
	     {"out", outDir}});
	const bool localized = session.localize();
	if (localized) session.run(queue, g_stop);
	base->stop();
	sweeps.stop();
	save();
	nlohmann::json end = session.status();
	end["navlog"] = session.finishNavLog();
	end["event"] = "end";
	end["rawlog"] = live.recordPath;
	end["signal"] = g_stop.load();
#ifdef SEMNAV_HAVE_ROS1
	if (rosOut)
	{
		const auto st = rosOut->stats();
		end["ros"] = {{"maps", st.maps},   {"paths", st.paths},
		              {"poses", st.poses}, {"sweeps", st.sweeps},
		              {"goals", st.goals}, {"max_hook_ms", st.maxHookMs}};
	}
#endif
	printEvent(end);
	g_publish = nullptr;
	// Bad commands were answered one by one; the run itself succeeded.
	return localized ? 0 : 1;
}
}  // namespace

int main(int argc, char** argv)
{
	semnav::CommandLine cli(
	    "semnav-robot",
	    "The headless navigation app on the robot: live sweeps from the "
	    "tilting LMS2xx, the robot base (ROS 1), the map growing as it "
	    "drives. Commands one per line on stdin (\"go to the nearest "
	    "<label>\", \"go to <label> <id>\", \"go to <x> <y>\", \"stop\", "
	    "\"status\", \"save map\"); JSON progress on stdout; the end of "
	    "stdin, SIGINT or SIGTERM ends the run (base stopped, map saved).");
	auto& cmd = cli.cmd();
	TCLAP::ValueArg<std::string> argConfig(
	    "", "config", "The robot INI", false,
	    semnav::ShippedConfig::path("robot.ini"), "robot.ini", cmd);
	TCLAP::ValueArg<std::string> argMap(
	    "", "map", "Starting map directory (overrides map_dir)", false, "",
	    "DIR", cmd);
	TCLAP::ValueArg<std::string> argPlugin(
	    "", "plugin",
	    "Robot base driver from a shared library (base = plugin; its INI "
	    "section is the plugin's name)",
	    false, "", "libX.so", cmd);
	TCLAP::ValueArg<std::string> argOut(
	    "", "out", "Output directory (overrides out_dir)", false, "", "DIR",
	    cmd);
	TCLAP::SwitchArg argNoStdin(
	    "", "no-stdin",
	    "Read no commands from stdin (a ROS node: commands on the command "
	    "topic; SIGINT or SIGTERM ends the run)",
	    cmd);
	if (const auto code = cli.parse(argc, argv)) return *code;
	std::signal(SIGINT, onSignal);
	std::signal(SIGTERM, onSignal);
	return cli.run(
	    [&]
	    {
		    std::unique_ptr<semnav::RobotBasePlugin> plugin;
		    if (!argPlugin.getValue().empty())
			    plugin = std::make_unique<semnav::RobotBasePlugin>(
			        argPlugin.getValue());
		    semnav::RobotSetup setup = semnav::RobotSetup::load(
		        argConfig.getValue(), plugin ? plugin->name() : "");
		    if (!argMap.getValue().empty())
			    setup.files.mapDir =
			        std::filesystem::absolute(argMap.getValue()).string();
		    const std::string out = argOut.getValue().empty()
		                                ? setup.resolve(setup.files.outDir)
		                                : argOut.getValue();
		    return runRobot(setup, plugin.get(), out, !argNoStdin.getValue());
	    });
}
