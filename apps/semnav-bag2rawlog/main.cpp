/* semnav: semantic navigation from tilting-laser sweeps */
// semnav-bag2rawlog: a ROS 1 bag of a tilting laser -> the rawlog
// semnav-map reads (docs/ros-bags.md).
#include <mrpt/core/bits_math.h>
#include <semnav/common/CommandLine.h>
#include <semnav/common/ProgressBar.h>
#include <semnav/ros1/BagToRawlog.h>

#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace
{
std::optional<semnav::BagToRawlog::Source> sourceNamed(
    const std::string& name, const std::string& topicName)
{
	if (name == topicName) return semnav::BagToRawlog::Source::Topic;
	if (name == "tf") return semnav::BagToRawlog::Source::Tf;
	return std::nullopt;
}

void printSummary(
    const semnav::BagToRawlog::Result& r, const std::string& bag,
    const std::string& out)
{
	std::cout << "semnav-bag2rawlog: " << bag << " -> " << out << ": "
	          << r.lines << " scan lines, " << r.odometry
	          << " odometry readings, " << (r.lastStamp - r.firstStamp)
	          << " s\n";
	if (r.skipped() > 0)
		std::cout << "  skipped " << r.skipped() << " of " << r.scans
		          << " scans: " << r.skippedNoTilt << " without a tilt, "
		          << r.skippedNoOdometry << " without odometry, "
		          << r.skippedBadScan << " malformed; first: " << r.firstSkip
		          << "\n";
}

nlohmann::json summaryJson(
    const semnav::BagToRawlog::Result& r, const std::string& out)
{
	return {
	    {"rawlog", out},
	    {"scans", r.scans},
	    {"lines", r.lines},
	    {"odometry", r.odometry},
	    {"skipped_no_tilt", r.skippedNoTilt},
	    {"skipped_no_odometry", r.skippedNoOdometry},
	    {"skipped_bad_scan", r.skippedBadScan},
	    {"first_skip", r.firstSkip},
	    {"first_stamp", r.firstStamp},
	    {"last_stamp", r.lastStamp}};
}
}  // namespace

int main(int argc, char** argv)
{
	semnav::CommandLine cli(
	    "semnav-bag2rawlog",
	    "Converts a ROS 1 bag of a tilting laser (sensor_msgs/LaserScan, the "
	    "tilt from sensor_msgs/JointState or tf, odometry from "
	    "nav_msgs/Odometry or tf) into the rawlog semnav-map reads.");
	auto& cmd = cli.cmd();
	semnav::BagToRawlog::TOptions o;
	TCLAP::UnlabeledValueArg<std::string> argBag(
	    "bag", "Input ROS 1 bag", true, "", "BAG", cmd);
	TCLAP::ValueArg<std::string> argOut(
	    "", "out", "Rawlog to write (atomically); required", false, "",
	    "R.rawlog", cmd);
	TCLAP::ValueArg<std::string> argScan(
	    "", "scan-topic", "sensor_msgs/LaserScan topic", false, o.scanTopic,
	    "T", cmd);
	TCLAP::ValueArg<std::string> argTiltFrom(
	    "", "tilt-from",
	    "Tilt from a joint of sensor_msgs/JointState or from tf (the laser "
	    "frame in the base frame)",
	    false, "joint_states", "joint_states|tf", cmd);
	TCLAP::ValueArg<std::string> argJoints(
	    "", "joint-states-topic", "sensor_msgs/JointState topic", false,
	    o.jointStatesTopic, "T", cmd);
	TCLAP::ValueArg<std::string> argJoint(
	    "", "tilt-joint", "Name of the tilt joint", false, o.tiltJoint, "NAME",
	    cmd);
	TCLAP::ValueArg<std::string> argAxis(
	    "", "tilt-axis",
	    "Axis of the tilt joint: +y (REP 103: a positive position lowers the "
	    "beam) or -y (raises it)",
	    false, "+y", "+y|-y", cmd);
	TCLAP::ValueArg<double> argOffset(
	    "", "tilt-offset-deg", "Added to the tilt read from the joint", false,
	    0, "DEG", cmd);
	TCLAP::ValueArg<std::string> argMount(
	    "", "mount",
	    "Tilt axis position in the base frame (joint_states tilt), m", false,
	    "0,0,0.45", "X,Y,Z", cmd);
	TCLAP::ValueArg<std::string> argOdomFrom(
	    "", "odom-from",
	    "Odometry from nav_msgs/Odometry or from tf (odom frame -> base "
	    "frame)",
	    false, "odometry", "odometry|tf", cmd);
	TCLAP::ValueArg<std::string> argOdom(
	    "", "odom-topic", "nav_msgs/Odometry topic", false, o.odomTopic, "T",
	    cmd);
	TCLAP::ValueArg<std::string> argBase(
	    "", "base-frame", "Robot frame (tf)", false, o.baseFrame, "F", cmd);
	TCLAP::ValueArg<std::string> argOdomFrame(
	    "", "odom-frame", "Odometry frame (tf)", false, o.odomFrame, "F", cmd);
	TCLAP::ValueArg<std::string> argLaser(
	    "", "laser-frame", "Laser frame (tf); default: the scans' frame_id",
	    false, "", "F", cmd);
	TCLAP::ValueArg<std::string> argLabel(
	    "", "sensor-label", "sensorLabel of the scan lines", false,
	    o.sensorLabel, "L", cmd);
	TCLAP::ValueArg<double> argGap(
	    "", "max-gap",
	    "Longest gap between the tilt positions around a line, and largest "
	    "age of its odometry message, s",
	    false, o.maxGap, "S", cmd);
	TCLAP::SwitchArg& argJson = cli.addJson();

	std::optional<mrpt::math::TPoint3D> mount;
	std::optional<semnav::BagToRawlog::Source> tiltFrom, odomFrom;
	cli.addCheck(
	    [&]() -> std::optional<std::string>
	    {
		    if (argOut.getValue().empty()) return "missing --out";
		    tiltFrom = sourceNamed(argTiltFrom.getValue(), "joint_states");
		    if (!tiltFrom)
			    return "--tilt-from must be joint_states or tf, got '" +
			           argTiltFrom.getValue() + "'";
		    odomFrom = sourceNamed(argOdomFrom.getValue(), "odometry");
		    if (!odomFrom)
			    return "--odom-from must be odometry or tf, got '" +
			           argOdomFrom.getValue() + "'";
		    if (argAxis.getValue() != "+y" && argAxis.getValue() != "-y")
			    return "--tilt-axis must be +y or -y, got '" +
			           argAxis.getValue() + "'";
		    if (const auto v =
		            semnav::CommandLine::parseNumbers(argMount.getValue(), 3))
			    mount = mrpt::math::TPoint3D((*v)[0], (*v)[1], (*v)[2]);
		    else
			    return "--mount must be X,Y,Z, got '" + argMount.getValue() +
			           "'";
		    if (!(argGap.getValue() > 0) || !std::isfinite(argGap.getValue()))
			    return "--max-gap must be > 0";
		    if (!std::isfinite(argOffset.getValue()))
			    return "--tilt-offset-deg must be finite";
		    if (argLabel.getValue().empty() ||
		        argLabel.getValue().find_first_of(" \t\r\n") !=
		            std::string::npos)
			    return "--sensor-label must be one word";
		    return std::nullopt;
	    });
	if (const auto code = cli.parse(argc, argv)) return *code;

	o.scanTopic = argScan.getValue();
	o.tiltFrom = *tiltFrom;
	o.jointStatesTopic = argJoints.getValue();
	o.tiltJoint = argJoint.getValue();
	o.tiltAxisNegative = argAxis.getValue() == "-y";
	o.tiltOffset = mrpt::DEG2RAD(argOffset.getValue());
	o.mount = *mount;
	o.odomFrom = *odomFrom;
	o.odomTopic = argOdom.getValue();
	o.baseFrame = argBase.getValue();
	o.odomFrame = argOdomFrame.getValue();
	o.laserFrame = argLaser.getValue();
	o.sensorLabel = argLabel.getValue();
	o.maxGap = argGap.getValue();

	return cli.run(
	    [&]
	    {
		    semnav::BagToRawlog converter(o);
		    // Scans of a long bag: redrawn every 100 (stderr, a terminal only).
		    std::optional<semnav::ProgressBar> bar;
		    const auto r = converter.convert(
		        argBag.getValue(), argOut.getValue(),
		        [&](std::size_t done, std::size_t total)
		        {
			        if (!bar) bar.emplace(total, "converting scans");
			        if (done % 100 == 0 || done == total) bar->update(done);
		        });
		    if (bar) bar->finish();
		    if (argJson.getValue())
			    std::cout << summaryJson(r, argOut.getValue()).dump()
			              << std::endl;
		    else
			    printSummary(r, argBag.getValue(), argOut.getValue());
		    return 0;
	    });
}
