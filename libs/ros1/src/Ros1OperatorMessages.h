/* semnav: semantic navigation from tilting-laser sweeps */
// The messages Ros1Operator publishes, built from copies of the session's
// state (no ROS I/O here).
#pragma once

#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <mrpt/math/TPose2D.h>
#include <nav_msgs/OccupancyGrid.h>
#include <nav_msgs/Path.h>
#include <semnav/common/GridGeometry.h>
#include <semnav/common/Label.h>
#include <semnav/map/ObjectInstance.h>
#include <semnav/nav/SemanticNavigator.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_msgs/TFMessage.h>
#include <visualization_msgs/MarkerArray.h>

#include <opencv2/core.hpp>
#include <vector>

namespace semnav
{
class SemanticMap;

namespace ros1msg
{
/** What the map topics need, copied from the map on the control thread
 * (the occupancy already converted). */
struct MapSnapshot
{
	nav_msgs::OccupancyGrid occupancy;
	GridGeometry geometry;
	/** "labels", "cost", "observations" layers (empty when absent). */
	std::vector<float> labels, cost, observations;
	double lethalCost = 1000;
	std::vector<ObjectInstance> instances;
};

MapSnapshot snapshot(const SemanticMap& map);

/** 100 where a cell has `label`, 0 where observed without it, -1 never
 * observed. */
nav_msgs::OccupancyGrid labelGrid(
    const MapSnapshot& m, Label label, const std_msgs::Header& header);
/** The travel cost u scaled to 0-100 (100: u >= L), -1 never observed. */
nav_msgs::OccupancyGrid costGrid(
    const MapSnapshot& m, const std_msgs::Header& header);
/** Per instance a box (namespace "objects") of its extent and a text
 * (namespace "labels") "<label> <id> (<n> obs)", both with the instance's
 * id; a DELETEALL first clears instances gone since. */
visualization_msgs::MarkerArray objectMarkers(
    const std::vector<ObjectInstance>& instances,
    const std_msgs::Header& header);
nav_msgs::Path path(
    const SemanticNavigator::PlanRecord& plan, const std_msgs::Header& header);
/** Covariance diag(stdXY^2, stdXY^2, 0, 0, 0, stdYaw^2). */
geometry_msgs::PoseWithCovarianceStamped pose(
    const mrpt::math::TPose2D& p, double stdXY, double stdYaw,
    const std_msgs::Header& header);
/** The transform mapFrame -> odomFrame that puts the odometry reading
 * `odometry` at the map pose `pose`. */
tf2_msgs::TFMessage mapToOdom(
    const mrpt::math::TPose2D& pose, const mrpt::math::TPose2D& odometry,
    const std_msgs::Header& header, const std::string& odomFrame);
/** Valid points of `points` (robot frame, CV_32FC3) at `at` in the map
 * frame, fields x y z label (float32, the label's id from `labels`,
 * CV_8U). */
sensor_msgs::PointCloud2 sweepCloud(
    const cv::Mat& points, const cv::Mat& labels, const mrpt::math::TPose2D& at,
    const std_msgs::Header& header);

}  // namespace ros1msg
}  // namespace semnav
