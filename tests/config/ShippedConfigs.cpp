/* semnav: semantic navigation from tilting-laser sweeps */
#include "ShippedConfigs.h"

#include <mrpt/config/CConfigFileMemory.h>
#include <semnav/cascade/CascadeTrainer.h>
#include <semnav/common/ConfigFileWriter.h>
#include <semnav/detection/CascadeDetector.h>
#include <semnav/hwdrivers/CTiltingLMS2xx.h>
#include <semnav/hwdrivers/LiveSweepSource.h>
#include <semnav/localization/GroundBorders.h>
#include <semnav/localization/Localizer.h>
#include <semnav/localization/ObjectFootprints.h>
#include <semnav/localization/PredictionGuard.h>
#include <semnav/localization/SemanticEvidenceMap.h>
#include <semnav/localization/SemanticExtractor.h>
#include <semnav/localization/WallExtractor.h>
#include <semnav/localization/WallMap.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/map/TravelCostModel.h>
#include <semnav/nav/RobotNavInterface.h>
#include <semnav/nav/SemanticNavigator.h>
#include <semnav/nav/StopAndScanLocalizer.h>
#include <semnav/nav/ViewPlanner.h>
#include <semnav/perception/NormalImage.h>
#include <semnav/perception/RangeSegmentation.h>
#include <semnav/perception/Roughness.h>
#include <semnav/perception/RuleClassifier.h>
#include <semnav/planning/CnnPlanner.h>
#include <semnav/planning/TraversabilityBuilder.h>
#include <semnav/robot/SweepObstacles.h>
#include <semnav/ros1/Ros1BaseOptions.h>
#include <semnav/ros1/Ros1OperatorOptions.h>
#include <semnav/runtime/RobotSetup.h>
#include <semnav/scan/SweepAssembler.h>
#include <semnav/sim/SimulatedRobot.h>
#include <semnav/sim/SimulatorOptions.h>
#include <semnav/training/SampleGenerator.h>

#include <algorithm>
#include <sstream>
#include <stdexcept>

namespace semnav::test
{
namespace
{
template <class T>
ShippedSection section(const std::string& name)
{
	return {name, [] { return std::make_unique<T>(); }};
}

const char* kGrabberSensorKeys = R"(driver = CTiltingLMS2xx
process_rate = 50
max_queue_len = 2000
sensorLabel = TILT_LMS
)";
/** [TILT_LMS] of a real LMS200 + PTU on the robot's ports, writing its
 * stats to `statsFile`. RS-232 at 38400 baud gives about 4.7 lines/s, so
 * 0.5 deg per line needs 2.34 deg/s (with an RS-422 adapter: COM_baudRate =
 * 500000, tilt_speed_deg_s = 18.75). */
std::string realHead(const std::string& statsFile)
{
	return R"(
[TILT_LMS]
COM_port_LIN = /dev/ttyUSB0
ptu_port = /dev/ttyUSB1
tilt_speed_deg_s = 2.34
stall_timeout_s = 1.0
reconnect_delay_s = 1.0
stats_file = )" +
	       statsFile + "\n";
}

/** A rawlog-grabber file: [global], then [TILT_LMS] with the grabber's
 * sensor keys and CTiltingLMS2xx's. */
ShippedConfig grabber(const std::string& file)
{
	ShippedConfig c;
	c.file = file;
	c.sections = {section<CTiltingLMS2xx::TOptions>("TILT_LMS")};
	c.foreignKeys = {{"TILT_LMS", kGrabberSensorKeys}};
	return c;
}
/** A semnav-robot file: the app's sections, the live sweep source, the ROS
 * base and the laser + head ([TILT_LMS] with the grabber's sensor keys). */
ShippedConfig robot(const std::string& file)
{
	ShippedConfig c;
	c.file = file;
	c.sections = {
	    section<RobotSetup::TOptions>("RobotSetup"),
	    section<RobotSession::TOptions>("SemnavRobot"),
	    section<LiveSweepSource::TOptions>("LiveSweepSource"),
	    section<Ros1BaseOptions>("Ros1Base"),
	    section<Ros1OperatorOptions>("Ros1Operator"),
	    section<CTiltingLMS2xx::TOptions>("TILT_LMS")};
	c.foreignKeys = {{"TILT_LMS", kGrabberSensorKeys}};
	return c;
}
}  // namespace

std::vector<ShippedConfig> shippedConfigs()
{
	std::vector<ShippedConfig> all;
	{
		ShippedConfig c;
		c.file = "cascade.ini";
		c.header =
		    "Haar cascade detection (paper sec. 2.2.2) and training: "
		    "semnav-detect,\n"
		    "semnav-train-cascade --config config/cascade.ini, "
		    "scripts/train-cascades.\n"
		    "Lengths m, sizes in detection-image pixels. Measurements: "
		    "docs/detection.md.";
		c.sections = {
		    section<CascadeDetector::TOptions>("CascadeDetector"),
		    section<SampleGenerator::TOptions>("SampleGenerator"),
		    section<CascadeTrainer::TOptions>("CascadeTrainer")};
		// Settings of the trained models in datasets/cascades/: the
		// search they were tuned with, each class's cascade, shape model
		// and plausibility limits, and the recipe they were trained with
		// (docs/detection.md). A retrained model comes with its own.
		c.overrides = R"(
[CascadeDetector]
measure_margin = 0.25
range_cut_m = 3.0
range_objects_only = true
range_scales = true
threads = 0
[CascadeDetector.washbasin]
cascade = ../datasets/cascades/washbasin.xml
max_elevation_deg = 60
far_upscale = 1.6
far_min_elevation_deg = -14
far_max_elevation_deg = 16
min_neighbors = 1
min_width_m = 0.15
min_top_m = 0.45
min_points = 100
border_px = 24
max_stages = 14
shape_model = ../datasets/cascades/washbasin-shape.xml.gz
segment_candidates = true
cascade_support = true
back_wall_length_m = 0.8
max_continuing_share = 0.3
min_flat_face_share = 0.6
min_shape_score = 0.4
[CascadeDetector.wastebasket]
cascade = ../datasets/cascades/wastebasket.xml
channel = view
max_elevation_deg = 30
far_upscale = 0
far_below_px = 0
far_min_elevation_deg = -16
far_max_elevation_deg = 8
min_neighbors = 1
min_points = 100
border_px = 24
max_stages = 10
shape_model = ../datasets/cascades/wastebasket-shape.xml.gz
segment_candidates = true
cascade_support = true
max_overhead_share = 0.7
min_shape_score = 0.4
[CascadeDetector.stairs]
cascade = ../datasets/cascades/stairs.xml
max_elevation_deg = 60
far_min_elevation_deg = -10
far_max_elevation_deg = 10
min_neighbors = 8
window_step = 2
min_width_m = 0.3
min_top_m = 0.35
max_top_m = 1.5
min_size_m = 0.5
min_cut_size_m = 0.4
max_stages = 14
shape_model = ../datasets/cascades/stairs-shape.xml.gz
segment_candidates = true
cascade_support = true
back_wall_length_m = 0.8
min_separation_m = 2
grow_m = 0.3
min_shape_score = 0.3
side_bearing_deg = 70
side_min_shape_score = 0.45
[SampleGenerator]
positives = 3000
min_object_pixels = 60
own_background_fraction = 0.5
[CascadeTrainer]
num_stages = 25
round_feature_fraction = 0.25
)";
		// A class's changes to [CascadeTrainer] (read by
		// semnav-train-cascade for that class only).
		c.foreignAfter =
		    R"(# Stairs are the most varied views (front, side, close): more stumps per stage.
[CascadeTrainer.stairs]
max_weak_count = 150

# Wastebaskets are small: a 12 x 12 window finds the far ones at upscale 2.
[CascadeTrainer.wastebasket]
window_width = 12
window_height = 12
)";
		all.push_back(c);
	}
	{
		ShippedConfig c = grabber("grabber-emulated.ini");
		c.header =
		    "rawlog-grabber + semnav's CTiltingLMS2xx against "
		    "semnav-device-emulator:\n"
		    "  semnav-device-emulator --scene datasets/office/office.yaml \\\n"
		    "      --lms-link /tmp/semnav-capture/lms --ptu-link "
		    "/tmp/semnav-capture/ptu &\n"
		    "  rawlog-grabber -p build/lib/libsemnav_hwdrivers.so "
		    "config/grabber-emulated.ini < /dev/tty\n"
		    "(rawlog-grabber stops at the first key on its stdin.) "
		    "scripts/capture-selftest\n"
		    "runs both with this file, rewriting the paths for its own "
		    "directory.";
		c.foreignBefore = R"([global]
rawlog_prefix = /tmp/semnav-capture/capture
time_between_launches = 0
use_sensoryframes = false
GRABBER_PERIOD_MS = 200
rawlog_GZ_compress_level = 1
)";
		// The emulator's links; 500 kbaud (RS-422): the LMS200's full 37.5
		// lines/s; timeouts for a busy machine's hiccups (0.5 s seen).
		c.overrides = R"(
[TILT_LMS]
COM_port_LIN = /tmp/semnav-capture/lms
COM_baudRate = 500000
ptu_port = /tmp/semnav-capture/ptu
stall_timeout_s = 1.0
reconnect_delay_s = 0.3
stats_file = /tmp/semnav-capture/stats.json
)";
		all.push_back(c);
	}
	{
		ShippedConfig c = grabber("grabber-tilting-lms200.ini");
		c.header =
		    "Capture with a real SICK LMS200 on a Directed Perception "
		    "pan-tilt unit:\n"
		    "  rawlog-grabber -p build/lib/libsemnav_hwdrivers.so "
		    "config/grabber-tilting-lms200.ini\n"
		    "(press a key in its terminal to stop). One "
		    "CObservation2DRangeScan per scan\n"
		    "line, the tilt of the line's time in its sensorPose "
		    "(libs/hwdrivers/README.md).";
		c.foreignBefore = R"([global]
rawlog_prefix = ./semnav-capture
time_between_launches = 300
use_sensoryframes = false
GRABBER_PERIOD_MS = 500
rawlog_GZ_compress_level = 1
)";
		c.overrides = realHead("./semnav-capture-stats.json");
		all.push_back(c);
	}
	all.push_back(
	    {"localization.ini",
	     "Localization (semnav-map --poses pf, semnav-nav --localize; "
	     "--loc-config\nconfig/localization.ini): particle filter on wall "
	     "landmarks with main-direction\nheading correction (paper sec. "
	     "2.3), the semantic evidence of each sweep\n(labels and detected "
	     "objects against the map's) and, while mapping, the\nobject "
	     "footprints (posts, bins) against those of earlier sweeps and the\n"
	     "prediction guard (directions the sweep does not constrain follow "
	     "the\nodometry).",
	     {section<WallExtractor::TOptions>("WallExtractor"),
	      section<WallMap::TOptions>("WallMap"),
	      section<Localizer::TOptions>("Localizer"),
	      section<SemanticExtractor::TOptions>("SemanticExtractor"),
	      section<SemanticEvidenceMap::TOptions>("SemanticEvidence"),
	      section<ObjectFootprints::TOptions>("ObjectFootprints"),
	      section<PredictionGuard::TOptions>("PredictionGuard"),
	      section<GroundBorders::TOptions>("GroundBorders")}});
	{
		ShippedConfig c{
		    "map.ini",
		    "semnav-map options (semnav-map --config config/map.ini). The "
		    "perception\nsections of config/perception.ini may be added "
		    "here too.",
		    {section<SemanticMap::TOptions>("SemanticMap"),
		     section<TravelCostModel::TOptions>("TravelCost"),
		     section<SweepAssembler::TOptions>("SweepAssembler")}};
		// semnav-map's own default (MapBuilder::Settings): a robot's
		// recording holds every nod, most taken while driving.
		c.overrides = R"(
[SweepAssembler]
drop_motion_fragments = true
)";
		all.push_back(c);
	}
	all.push_back(
	    {"navigation.ini",
	     "semnav navigation (semnav-nav, scripts/demo): the CNN path "
	     "handed to MRPT's\nreactive navigator as waypoints, stop-and-scan "
	     "localization, the robot\ninterface MRPT drives (obstacles from "
	     "the latest stop's sweeps) and MRPT's own\nreactive-navigation "
	     "sections "
	     "(RobotModel_circular_shape_radius must match\nrobot_radius_m of "
	     "config/planning.ini and of [SimulatedRobot] in config/sim.ini).",
	     {section<SemanticNavigator::TOptions>("SemanticNavigator"),
	      section<StopAndScanLocalizer::TOptions>("StopAndScan"),
	      section<ViewPlanner::TOptions>("ViewPlanner"),
	      section<RobotNavInterface::TOptions>("RobotNavInterface"),
	      section<SweepObstacles::TOptions>("SweepObstacles")},
	     "",
	     {},
	     "",
	     "",
	     "# ---- MRPT reactive navigation"});
	all.push_back(
	    {"perception.ini",
	     "semnav perception (semnav-perceive --config): normal image, "
	     "range\nsegmentation, roughness and the rule-based classifier "
	     "(paper sec. 2.1-2.2.1).",
	     {section<NormalImage::TOptions>("NormalImage"),
	      section<RangeSegmentation::TOptions>("RangeSegmentation"),
	      section<Roughness::TOptions>("Roughness"),
	      section<RuleClassifier::TOptions>("RuleClassifier")}});
	all.push_back(
	    {"planning.ini",
	     "semnav path planning (CNN planner of the paper's sec. 3), used "
	     "by\nsemnav-plan and semnav-nav. Path cost: sum over steps of "
	     "(step length + u of\nthe cell entered).",
	     {section<CnnPlanner::TOptions>("CnnPlanner"),
	      section<TraversabilityBuilder::TOptions>("Traversability")}});
	{
		ShippedConfig c = robot("robot.ini");
		c.header =
		    "semnav-robot on a real robot: a SICK LMS200 on a Directed "
		    "Perception PTU\n(the [TILT_LMS] keys of "
		    "config/grabber-tilting-lms200.ini) and a robot base\nover ROS 1 "
		    "(cmd_vel out, odom in):\n"
		    "  semnav-robot --config config/robot.ini --map MAPDIR\n"
		    "then type commands (\"go to the nearest wastebasket\", "
		    "\"status\", \"save map\";\nCtrl-D or Ctrl-C ends the run, the "
		    "base stopped and the map saved).\nFor another base: base = "
		    "plugin and semnav-robot --plugin libX.so (its\nsection is the "
		    "plugin's name). docs/hardware.md.";
		// The robot's recording survives a crash (RawlogWriter Streaming).
		c.overrides = "\n[LiveSweepSource]\nrecord_streaming = true" +
		              realHead("./semnav-robot-out/laser-stats.json");
		all.push_back(c);
	}
	{
		ShippedConfig c = robot("robot-emulated.ini");
		c.header =
		    "semnav-robot driving the emulated robot "
		    "(semnav-device-emulator --base: the\nLMS200 + PTU on "
		    "pseudo-terminals riding a differential-drive base that\nspeaks "
		    "ROS 1); scripts/robot-selftest runs both with this file, "
		    "rewriting\nthe paths for its own directory. The tilt runs at "
		    "37.5 deg/s (1 deg per line\nat the 500 kbaud link's 37.5 "
		    "lines/s): a 2.8 s sweep, half the resolution of\nthe capture "
		    "config, to keep a run within a few minutes.";
		c.overrides = R"(
[RobotSetup]
out_dir = /tmp/semnav-robot/out
[SemnavRobot]
laser_silence_s = 0.2
[LiveSweepSource]
record_streaming = true
[TILT_LMS]
COM_port_LIN = /tmp/semnav-robot/lms
COM_baudRate = 500000
ptu_port = /tmp/semnav-robot/ptu
tilt_speed_deg_s = 37.5
stall_timeout_s = 1.0
reconnect_delay_s = 0.3
stats_file = /tmp/semnav-robot/laser-stats.json
)";
		all.push_back(c);
	}
	all.push_back(
	    {"sim.ini",
	     "The simulator: [Simulator] for semnav-sim (--config "
	     "config/sim.ini), the\nsimulated robot [SimulatedRobot] for "
	     "semnav-nav (--sim-config config/sim.ini).",
	     {section<SimulatorOptions>("Simulator"),
	      section<SimulatedRobot::TOptions>("SimulatedRobot")}});
	const std::string common =
	    "\nEvery key is optional; the values below are the code's defaults "
	    "except where\nmarked \"(default: ...)\" (docs/configuration.md). "
	    "Unknown sections or keys\nand out-of-range values are errors.";
	for (auto& c : all) c.header += common;
	return all;
}

namespace
{
/** `text` with each key whose value differs from `defaults` marked
 * "(default: <value>)" at the end of its comment line. */
std::string markOverrides(const std::string& text, const std::string& defaults)
{
	mrpt::config::CConfigFileMemory d(defaults);
	std::istringstream in(text);
	std::vector<std::string> lines;
	std::string section;
	for (std::string line; std::getline(in, line);)
	{
		if (!line.empty() && line[0] == '[')
			section = line.substr(1, line.find(']') - 1);
		const auto eq = line.find(" = ");
		if (line.empty() || line[0] == '#' || eq == std::string::npos)
		{
			lines.push_back(line);
			continue;
		}
		const std::string key = line.substr(0, eq);
		const std::string value = line.substr(eq + 3);
		if (d.keyExists(section, key))
		{
			const std::string dflt = d.read_string(section, key, "");
			if (dflt != value && !lines.empty() &&
			    lines.back().rfind("# ", 0) == 0)
				lines.back() +=
				    " (default: " + (dflt.empty() ? "empty" : dflt) + ")";
		}
		lines.push_back(line);
	}
	std::string out;
	for (const auto& l : lines) out += l + "\n";
	return out;
}
}  // namespace

std::string expectedText(const ShippedConfig& spec, const std::string& current)
{
	mrpt::config::CConfigFileMemory overrides(spec.overrides);
	std::vector<std::string> overridden;
	overrides.getAllSections(overridden);
	for (const auto& name : overridden)
		if (std::none_of(
		        spec.sections.begin(), spec.sections.end(),
		        [&](const ShippedSection& s)
		        {
			        // [Section.<label>]: read by [Section]'s options.
			        return s.name == name || name.rfind(s.name + ".", 0) == 0;
		        }))
			throw std::runtime_error(
			    spec.file + ": override of [" + name +
			    "], which the file does not hold");
	std::vector<std::unique_ptr<mrpt::config::CLoadableOptions>> structs;
	std::string text;
	{
		std::string header;
		for (std::size_t b = 0; b < spec.header.size();)
		{
			auto e = spec.header.find('\n', b);
			if (e == std::string::npos) e = spec.header.size();
			header += "# " + spec.header.substr(b, e - b) + "\n";
			b = e + 1;
		}
		text = header;
	}
	if (!spec.foreignBefore.empty()) text += "\n" + spec.foreignBefore;
	for (const auto& s : spec.sections)
	{
		const auto defaults = s.make();
		structs.push_back(s.make());
		structs.back()->loadFromConfigFile(overrides, s.name);
		std::string part = markOverrides(
		    configText({{s.name, structs.back().get()}}),
		    configText({{s.name, defaults.get()}}));
		for (const auto& [name, keys] : spec.foreignKeys)
			if (name == s.name) part.insert(part.find('\n') + 1, keys);
		text += "\n" + part;
	}
	if (!spec.foreignAfter.empty()) text += "\n" + spec.foreignAfter;
	if (!spec.keptTailMarker.empty())
	{
		const auto at = current.find("\n" + spec.keptTailMarker);
		if (at != std::string::npos) text += current.substr(at);
	}
	return text;
}

}  // namespace semnav::test
