/* semnav: semantic navigation from tilting-laser sweeps */
// semnav-device-emulator: a SICK LMS200 and a Directed Perception PTU on
// pseudo-terminals, scanning a scene (emulate mode), optionally carried by
// an emulated differential-drive base speaking ROS 1 (--base); or the check
// of a rawlog captured from them against the scene (--check).
#include <mrpt/core/bits_math.h>
#include <semnav/common/CommandLine.h>
#include <semnav/common/Error.h>
#include <semnav/emulation/CaptureCheck.h>
#include <semnav/emulation/EmulatedDiffDriveBase.h>
#include <semnav/emulation/SceneLineCaster.h>
#include <semnav/emulation/TiltingScannerEmulator.h>
#include <semnav/sim/SceneLoader.h>
#include <sys/resource.h>
#ifdef SEMNAV_HAVE_ROS1
#include <semnav/emulation/Ros1BaseEmulator.h>
#endif

#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <thread>

namespace
{
std::atomic<bool> g_stop{false};
void onSignal(int)
{
	g_stop = true;
}

std::optional<double> parseNumber(const std::string& s)
{
	if (s.empty()) return std::nullopt;
	char* end = nullptr;
	const double v = std::strtod(s.c_str(), &end);
	if (!end || *end != '\0' || !std::isfinite(v)) return std::nullopt;
	return v;
}

/** The summary of a capture check, merged with the driver's stats file
 * and the tilts of the emulator's truth log when given. */
nlohmann::json checkJson(
    const semnav::CaptureCheckResult& r, const std::string& rawlog,
    const std::string& stats, const std::string& truthLog)
{
	nlohmann::json j;
	if (!stats.empty())
	{
		std::ifstream f(stats);
		if (!f) throw semnav::IoError("cannot read " + stats);
		try
		{
			j = nlohmann::json::parse(f);
		}
		catch (const std::exception&)
		{
			throw semnav::IoError(stats + " is not JSON");
		}
		j["driver_lines"] = j.value("lines", 0);
		j["driver_sweeps_complete"] = j.value("sweeps_complete", 0);
		j.erase("sweeps_complete");
	}
	j["rawlog"] = rawlog;
	j["objects"] = r.objects;
	j["lines"] = r.lines;
	j["sweeps"] = r.sweepsComplete;
	j["sweeps_incomplete"] = r.sweepsIncomplete;
	j["truncated"] = r.truncated;
	j["truncation"] = r.truncation;
	j["pixels"] = r.pixels;
	j["median_abs_error_m"] = r.medianAbsError;
	j["within_3sigma"] = r.within3Sigma;
	j["within_3sigma_1step"] = r.within3SigmaTilt;
	j["spurious"] = r.spurious;
	j["missed"] = r.missed;
	nlohmann::json list = nlohmann::json::array();
	for (const auto& sw : r.sweeps)
		list.push_back(
		    {{"rows", sw.rows},
		     {"cols", sw.cols},
		     {"pixels", sw.pixels},
		     {"within_3sigma_1step", sw.within3SigmaTilt},
		     {"missing_lines", sw.missingLines},
		     {"theta_min_deg", mrpt::RAD2DEG(sw.thetaMin)},
		     {"theta_max_deg", mrpt::RAD2DEG(sw.thetaMax)},
		     {"complete", sw.complete}});
	j["sweep_list"] = list;
	if (!truthLog.empty())
	{
		const auto t = semnav::checkTilts(rawlog, truthLog);
		j["tilt_matched"] = t.matched;
		j["tilt_median_abs_error_deg"] = t.medianAbsErrorDeg;
		j["tilt_p95_abs_error_deg"] = t.p95AbsErrorDeg;
		j["time_median_offset_ms"] = t.medianTimeOffsetMs;
	}
	if (!j.contains("crc_errors")) j["crc_errors"] = nullptr;
	return j;
}
/** Why the robot cannot stand at `p` in `scene`, if it cannot. */
std::optional<std::string> poseProblem(
    const semnav::Scene& scene, const mrpt::math::TPose2D& p)
{
	const auto& b = scene.bounds;
	if (!b.contains(p.x, p.y))
	{
		std::ostringstream os;
		os << "is outside the bounds [" << b.xmin << ", " << b.ymin << ", "
		   << b.xmax << ", " << b.ymax << "]";
		return os.str();
	}
	if (const auto i = scene.obstacleAt(p.x, p.y))
	{
		const auto& o = scene.objects[*i];
		return "is inside objects[" + std::to_string(*i) + "] (" +
		       semnav::labelName(o.label) + ", line " + std::to_string(o.line) +
		       ")";
	}
	return std::nullopt;
}

/** The emulated base's summary. */
nlohmann::json baseJson(const semnav::EmulatedDiffDriveBase& base)
{
	const auto s = base.state();
	const auto pose = [](const mrpt::math::TPose2D& p) {
		return nlohmann::json{p.x, p.y, mrpt::RAD2DEG(p.phi)};
	};
	return {{"true_pose", pose(s.truePose)},
	        {"odometry_pose", pose(s.odometry.pose)},
	        {"distance_m", s.odometry.distance},
	        {"collisions", s.collisions},
	        {"watchdog_stops", s.watchdogStops},
	        {"base_commands", s.commands}};
}

/** How the base speaks ROS (--odom-rate, --node-name, --odom-silent-*). */
struct BaseLink
{
	double odomRate = 50;
	std::string nodeName;
	double silentAt = -1, silentFor = 0;
};

/** The emulated ROS base around `base` when asked (and built with ROS). */
struct BaseServer
{
#ifdef SEMNAV_HAVE_ROS1
	std::unique_ptr<semnav::Ros1BaseEmulator> ros;
#endif
	/** Its topics and master (null without a base). */
	nlohmann::json topics;
	BaseServer(semnav::EmulatedDiffDriveBase* base, const BaseLink& link)
	{
		if (!base) return;
#ifdef SEMNAV_HAVE_ROS1
		semnav::Ros1BaseEmulator::Options o;
		o.odomRate = link.odomRate;
		o.nodeName = link.nodeName;
		o.odomSilentAt = link.silentAt;
		o.odomSilentFor = link.silentFor;
		ros = std::make_unique<semnav::Ros1BaseEmulator>(*base, o);
		const char* master = std::getenv("ROS_MASTER_URI");
		topics = {
		    {"cmd_vel", o.cmdVelTopic},
		    {"odom", o.odomTopic},
		    {"ground_truth", o.truthTopic},
		    {"master", master ? master : ""}};
#else
		(void)link;
		throw semnav::Error("--base needs ROS 1: this build has none");
#endif
	}
};

/** Serves the emulated devices (and the base when given) until a signal or
 * `duration` s (when > 0), printing their terminals, then their counters. */
void emulate(
    const semnav::Scene& scene, semnav::LmsEmulator::Options lms,
    const std::string& ptuLink, double duration, bool json,
    semnav::EmulatedDiffDriveBase* base, const BaseLink& link)
{
	if (base)
	{
		lms.poseSource = [base] { return base->truePose(); };
		base->start();
	}
	BaseServer server(base, link);
	semnav::TiltingScannerEmulator devices(scene, lms, ptuLink);
	devices.start();
	const auto& l = devices.lms();
	const auto& p = devices.ptu();
	nlohmann::json paths{
	    {"lms", l.devicePath()},
	    {"ptu", p.devicePath()},
	    {"lms_pts", l.slavePath()},
	    {"ptu_pts", p.slavePath()}};
	if (base) paths["base"] = server.topics;
	if (json)
		std::cout << paths.dump() << std::endl;
	else
	{
		std::cout << "LMS200 " << l.devicePath() << "\nPTU " << p.devicePath()
		          << std::endl;
		if (base) std::cout << "base " << server.topics.dump() << std::endl;
	}
	std::signal(SIGINT, onSignal);
	std::signal(SIGTERM, onSignal);
	const auto t0 = std::chrono::steady_clock::now();
	while (!g_stop)
	{
		std::this_thread::sleep_for(std::chrono::milliseconds(50));
		if (duration > 0 &&
		    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0)
		            .count() > duration)
			break;
	}
	devices.stop();
	if (base) base->stop();
	const auto c = l.counters();
	nlohmann::json j{
	    {"scans_sent", c.scansSent},
	    {"crc_injected", c.crcInjected},
	    {"bytes_dropped", c.bytesDropped},
	    {"commands", c.commands},
	    {"nacks", c.nacks},
	    {"stalls", c.stalls},
	    {"disconnects", c.disconnects},
	    {"ptu_commands", p.commands()}};
	if (base) j.update(baseJson(*base));
	if (json)
		std::cout << j.dump() << std::endl;
	else
		std::cout << "emulator: " << j.dump() << std::endl;
}
/** The command line's arguments, registered with `cmd` in this order. */
struct EmulatorArgs
{
	explicit EmulatorArgs(TCLAP::CmdLine& c) : cmd(c) {}
	TCLAP::CmdLine& cmd;
	TCLAP::ValueArg<std::string> argScene{
	    "", "scene", "Scene file (YAML); required", false, "", "S.yaml", cmd};
	TCLAP::ValueArg<std::string> argPose{
	    "",
	    "pose",
	    "Robot pose X,Y,YAW_DEG (default: first trajectory pose)",
	    false,
	    "",
	    "X,Y,YAW_DEG",
	    cmd};
	TCLAP::ValueArg<std::string> argLmsLink{
	    "",    "lms-link", "Symlink kept pointing at the LMS terminal",
	    false, "",         "PATH",
	    cmd};
	TCLAP::ValueArg<std::string> argPtuLink{
	    "",    "ptu-link", "Symlink kept pointing at the PTU terminal",
	    false, "",         "PATH",
	    cmd};
	TCLAP::ValueArg<int> argBaud{
	    "",    "lms-baud", "LMS power-on baud rate (9600, 38400, 500000)",
	    false, 9600,       "N",
	    cmd};
	TCLAP::ValueArg<std::string> argSeed{
	    "", "seed", "Range-noise seed; default 1", false, "1", "N", cmd};
	TCLAP::ValueArg<std::string> argCrc{
	    "",
	    "crc-error-rate",
	    "Fraction of scan telegrams with a bad CRC",
	    false,
	    "0",
	    "P",
	    cmd};
	TCLAP::ValueArg<std::string> argDrop{
	    "",
	    "drop-byte-rate",
	    "Fraction of scan telegrams missing one byte",
	    false,
	    "0",
	    "P",
	    cmd};
	TCLAP::ValueArg<std::string> argStallAt{
	    "",
	    "stall-at",
	    "LMS goes silent S seconds after its continuous output started",
	    false,
	    "-1",
	    "S",
	    cmd};
	TCLAP::ValueArg<std::string> argStallFor{
	    "", "stall-for", "... for D seconds", false, "2", "D", cmd};
	TCLAP::ValueArg<std::string> argDiscAt{
	    "",
	    "disconnect-at",
	    "LMS unplugged S seconds after its continuous output started",
	    false,
	    "-1",
	    "S",
	    cmd};
	TCLAP::ValueArg<std::string> argDiscFor{
	    "", "disconnect-for", "... for D seconds", false, "2", "D", cmd};
	TCLAP::ValueArg<std::string> argDuration{
	    "",    "duration", "Stop after S seconds, S > 0 (default: at a signal)",
	    false, "",         "S",
	    cmd};
	TCLAP::ValueArg<std::string> argCheck{
	    "",    "check", "Check mode: the captured rawlog to compare",
	    false, "",      "R.rawlog",
	    cmd};
	TCLAP::SwitchArg argTruncatedOk{
	    "", "truncated-ok",
	    "Check mode: a rawlog cut short (writer killed) is checked as far as "
	    "it goes and exits 0 (default: exit 1 after the JSON, with a line "
	    "saying where it ends)",
	    cmd};
	TCLAP::ValueArg<std::string> argStats{
	    "",    "stats", "Check mode: the driver's stats_file to merge",
	    false, "",      "F.json",
	    cmd};
	TCLAP::ValueArg<std::string> argTruth{
	    "",
	    "truth-log",
	    "Emulate: write each scan's time and true tilt here; check: compare "
	    "the lines' tilts with it",
	    false,
	    "",
	    "F.txt",
	    cmd};
	TCLAP::SwitchArg argBase{
	    "", "base",
	    "Emulate: the devices ride a differential-drive base from --pose, "
	    "speaking ROS 1 (cmd_vel in; odom and base_pose_ground_truth out) "
	    "on ROS_MASTER_URI",
	    cmd};
	TCLAP::ValueArg<std::string> argWatchdog{
	    "",    "base-watchdog", "The base stops after S s without cmd_vel",
	    false, "0.3",           "S",
	    cmd};
	TCLAP::ValueArg<std::string> argOdomRate{
	    "",   "odom-rate", "Odometry messages per second", false, "50",
	    "HZ", cmd};
	TCLAP::ValueArg<std::string> argOdomSilentAt{
	    "",
	    "odom-silent-at",
	    "The base's odometry goes silent S s after the first cmd_vel",
	    false,
	    "-1",
	    "S",
	    cmd};
	TCLAP::ValueArg<std::string> argOdomSilentFor{
	    "", "odom-silent-for", "... for D seconds", false, "2", "D", cmd};
	TCLAP::ValueArg<std::string> argTrajectory{
	    "",
	    "trajectory",
	    "The base's true trajectory: one line per step (time x y phi v w)",
	    false,
	    "",
	    "F.txt",
	    cmd};
	TCLAP::ValueArg<std::string> argNode{"",
	                                     "node-name",
	                                     "ROS node name of the base",
	                                     false,
	                                     "semnav_emulated_base",
	                                     "NAME",
	                                     cmd};
};

/** The numeric options into `num` by name; the first problem as a usage
 * error message. */
std::optional<std::string> readNumbers(
    EmulatorArgs& a, std::map<std::string, double>& num)
{
	for (auto* arg :
	     {&a.argSeed, &a.argCrc, &a.argDrop, &a.argStallAt, &a.argStallFor,
	      &a.argDiscAt, &a.argDiscFor, &a.argWatchdog, &a.argOdomRate,
	      &a.argOdomSilentAt, &a.argOdomSilentFor})
	{
		const auto v = parseNumber(arg->getValue());
		if (!v)
			return std::string(
			    "--" + arg->getName() + " must be a number, got '" +
			    arg->getValue() + "'");
		num[arg->getName()] = *v;
	}
	num["duration"] = 0;  // until a signal
	if (!a.argDuration.getValue().empty())
	{
		const auto d = parseNumber(a.argDuration.getValue());
		if (!d || !(*d > 0))
			return std::string(
			    "--duration must be a number of seconds > 0, got '" +
			    a.argDuration.getValue() + "'");
		num["duration"] = *d;
	}
	for (const char* p : {"crc-error-rate", "drop-byte-rate"})
		if (num[p] < 0 || num[p] > 1)
			return std::string("--") + p + " must be in [0, 1]";
	if (num["base-watchdog"] < 0.02 || num["base-watchdog"] > 10)
		return std::string("--base-watchdog must be in [0.02, 10]");
	if (num["odom-silent-for"] < 0)
		return std::string("--odom-silent-for must be >= 0");
	if (num["odom-rate"] < 1 || num["odom-rate"] > 1000)
		return std::string("--odom-rate must be in [1, 1000]");
	return std::nullopt;
}

}  // namespace

int main(int argc, char** argv)
{
	semnav::CommandLine cli(
	    "semnav-device-emulator",
	    "Emulates a SICK LMS200 (LMS2xx telegrams) and a Directed Perception "
	    "PTU (ASCII) on pseudo-terminals, scanning a scene; prints their "
	    "paths and runs until SIGINT/SIGTERM or --duration. With --check R, "
	    "compares a captured rawlog with the scene instead.");
	EmulatorArgs args(cli.cmd());
	TCLAP::SwitchArg& argJson = cli.addJson();
	if (const auto code = cli.parse(argc, argv)) return *code;
	if (args.argScene.getValue().empty())
		return cli.usageError("missing --scene");
	std::optional<mrpt::math::TPose2D> pose;
	if (!args.argPose.getValue().empty())
	{
		pose = semnav::CommandLine::parsePose(args.argPose.getValue());
		if (!pose)
			return cli.usageError(
			    "--pose must be X,Y,YAW_DEG, got '" + args.argPose.getValue() +
			    "'");
	}
	std::map<std::string, double> num;
	if (const auto problem = readNumbers(args, num))
		return cli.usageError(*problem);
	const int baud = args.argBaud.getValue();
	if (baud != 9600 && baud != 38400 && baud != 500000)
		return cli.usageError("--lms-baud must be 9600, 38400 or 500000");
	const bool json = argJson.getValue();

	return cli.run(
	    [&]
	    {
		    const semnav::Scene scene =
		        semnav::SceneLoader::loadFile(args.argScene.getValue());
		    if (!pose)
		    {
			    if (scene.trajectory.empty())
				    throw semnav::Error(
				        args.argScene.getValue() +
				        ": no trajectory pose; give --pose");
			    pose = scene.trajectory.front();
		    }
		    if (const auto problem = poseProblem(scene, *pose))
			    return cli.usageError(
			        "--pose " + args.argPose.getValue() + " " + *problem +
			        " of " + args.argScene.getValue());
		    if (!args.argCheck.getValue().empty())
		    {
			    const semnav::SceneLineCaster caster(scene);
			    const double res =
			        semnav::TiltingScannerEmulator::tiltResolution();
			    const auto check = semnav::checkCapture(
			        args.argCheck.getValue(), caster, *pose,
			        scene.sensor.rangeNoise, res,
			        scene.sensor.thetaMax - scene.sensor.thetaMin);
			    const auto j = checkJson(
			        check, args.argCheck.getValue(), args.argStats.getValue(),
			        args.argTruth.getValue());
			    if (json)
				    std::cout << j.dump() << std::endl;
			    else
				    std::cout << j.dump(2) << std::endl;
			    if (check.truncated && !args.argTruncatedOk.getValue())
				    throw semnav::RawlogError(
				        check.truncation + " (" +
				        std::to_string(check.objects) +
				        " objects before it checked)");
			    return 0;
		    }

		    // Devices answer within milliseconds whatever else the machine
		    // runs: raise our priority when allowed (the threads inherit it).
		    ::setpriority(PRIO_PROCESS, 0, -10);
		    semnav::LmsEmulator::Options lo;
		    lo.linkPath = args.argLmsLink.getValue();
		    lo.powerOnBaud = baud;
		    lo.robotPose = *pose;
		    lo.seed = static_cast<uint64_t>(num["seed"]);
		    lo.crcErrorRate = num["crc-error-rate"];
		    lo.dropByteRate = num["drop-byte-rate"];
		    lo.stallAt = num["stall-at"];
		    lo.stallFor = num["stall-for"];
		    lo.disconnectAt = num["disconnect-at"];
		    lo.disconnectFor = num["disconnect-for"];
		    lo.truthLog = args.argTruth.getValue();
		    std::unique_ptr<semnav::EmulatedDiffDriveBase> base;
		    if (args.argBase.getValue())
		    {
			    semnav::EmulatedDiffDriveBase::Options bo;
			    bo.watchdog = num["base-watchdog"];
			    bo.seed = lo.seed;
			    bo.trajectoryFile = args.argTrajectory.getValue();
			    base = std::make_unique<semnav::EmulatedDiffDriveBase>(
			        scene, *pose, bo);
		    }
		    emulate(
		        scene, lo, args.argPtuLink.getValue(), num["duration"], json,
		        base.get(),
		        {num["odom-rate"], args.argNode.getValue(),
		         num["odom-silent-at"], num["odom-silent-for"]});
		    return 0;
	    });
}
