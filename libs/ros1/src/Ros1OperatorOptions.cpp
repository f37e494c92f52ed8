/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/OptionTable.h>
#include <semnav/ros1/Ros1OperatorOptions.h>

#include <sstream>

namespace semnav
{
namespace
{
using O = Ros1OperatorOptions;

std::vector<Label> labelsFromNames(const std::string& text)
{
	std::vector<Label> out;
	std::istringstream in(text);
	for (std::string w; in >> w;) out.push_back(labelFromName(w));
	return out;
}

std::string namesOf(const std::vector<Label>& labels)
{
	std::string s;
	for (const auto l : labels) s += (s.empty() ? "" : " ") + labelName(l);
	return s;
}

const OptionTable<O>& optionTable()
{
	static const auto t =
	    OptionTable<O>()
	        .text(
	            "map_topic", &O::mapTopic,
	            "The occupancy, nav_msgs/OccupancyGrid, latched (empty: "
	            "none).")
	        .text(
	            "label_topic_prefix", &O::labelTopicPrefix,
	            "One nav_msgs/OccupancyGrid per label of label_layers on "
	            "PREFIX/<label>, latched (empty: none).")
	        .named(
	            "label_layers", &O::labelLayers, labelsFromNames, namesOf,
	            "Labels that get a grid (space-separated names).")
	        .text(
	            "cost_topic", &O::costTopic,
	            "Travel cost u as a 0-100 nav_msgs/OccupancyGrid (100: "
	            "blocked), latched (empty: none).")
	        .text(
	            "objects_topic", &O::objectsTopic,
	            "Object instances, visualization_msgs/MarkerArray (empty: "
	            "none).")
	        .text(
	            "path_topic", &O::pathTopic,
	            "The current plan, nav_msgs/Path (empty: none).")
	        .text(
	            "pose_topic", &O::poseTopic,
	            "The pose estimate, geometry_msgs/PoseWithCovarianceStamped "
	            "(empty: none).")
	        .text(
	            "sweep_topic", &O::sweepTopic,
	            "The last sweep, sensor_msgs/PointCloud2 with a label field "
	            "(empty: none).")
	        .text(
	            "goal_topic", &O::goalTopic,
	            "geometry_msgs/PoseStamped goals (rviz 2D Nav Goal) become "
	            "\"go to x y\" (empty: none).")
	        .text("map_frame", &O::mapFrame, "The map's frame.")
	        .text(
	            "odom_frame", &O::odomFrame,
	            "The odometry's frame (tf map -> odom).")
	        .flag("publish_tf", &O::publishTf, "Publish map -> odom on /tf.")
	        .real(
	            "map_period_s", &O::mapPeriod, 0.1, 3600,
	            "The map topics at most this often.")
	        .real(
	            "pose_rate_hz", &O::poseRate, 0.5, 100,
	            "Pose and tf at most this often.")
	        .check(
	            [](const O& o)
	            { return !o.mapFrame.empty() && !o.odomFrame.empty(); },
	            "map_frame and odom_frame must not be empty");
	return t;
}
}  // namespace

SEMNAV_OPTIONS_FROM_TABLE(Ros1OperatorOptions, optionTable())

}  // namespace semnav
