/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <semnav/common/Label.h>

#include <string>
#include <vector>

namespace semnav
{
/** Options of Ros1Operator, INI section [Ros1Operator] (config/robot.ini):
 * what semnav-robot shows an operator over ROS 1 and under which names.
 * An empty topic is not published. Built with or without ROS 1, so
 * configurations are checked everywhere. */
struct Ros1OperatorOptions : public mrpt::config::CLoadableOptions
{
	void loadFromConfigFile(
	    const mrpt::config::CConfigFileBase& c,
	    const std::string& section) override;
	void saveToConfigFile(
	    mrpt::config::CConfigFileBase& c,
	    const std::string& section) const override;

	/** map_topic: the occupancy as nav_msgs/OccupancyGrid (latched). */
	std::string mapTopic = "map";
	/** label_topic_prefix: one nav_msgs/OccupancyGrid per label of
	 * label_layers on PREFIX/<label> (100 where the cell has the label, 0
	 * where observed without it, -1 unobserved; latched). */
	std::string labelTopicPrefix = "semnav/labels";
	/** label_layers: the labels that get a grid. */
	std::vector<Label> labelLayers = {Label::Wall,        Label::Door,
	                                  Label::Stairs,      Label::Washbasin,
	                                  Label::Wastebasket, Label::Obstacle};
	/** cost_topic: the travel cost u as a 0-100 nav_msgs/OccupancyGrid
	 * (100: blocked, u >= L; -1 unobserved; latched). */
	std::string costTopic = "semnav/cost";
	/** objects_topic: object instances, visualization_msgs/MarkerArray. */
	std::string objectsTopic = "semnav/objects";
	/** path_topic: the current plan, nav_msgs/Path. */
	std::string pathTopic = "semnav/path";
	/** pose_topic: geometry_msgs/PoseWithCovarianceStamped. */
	std::string poseTopic = "semnav/pose";
	/** sweep_topic: the last sweep, sensor_msgs/PointCloud2 in the map
	 * frame with a `label` field. */
	std::string sweepTopic = "semnav/sweep";
	/** goal_topic: geometry_msgs/PoseStamped goals (rviz's 2D Nav Goal),
	 * each becomes "go to x y". */
	std::string goalTopic = "move_base_simple/goal";
	/** map_frame, odom_frame: frames of the map and of the odometry. */
	std::string mapFrame = "map";
	std::string odomFrame = "odom";
	/** publish_tf: map -> odom on /tf. */
	bool publishTf = true;
	/** map_period_s: the map topics at most this often. */
	double mapPeriod = 1.0;
	/** pose_rate_hz: pose and tf at most this often. */
	double poseRate = 10;
};

}  // namespace semnav
