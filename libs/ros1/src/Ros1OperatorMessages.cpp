/* semnav: semantic navigation from tilting-laser sweeps */
#include "Ros1OperatorMessages.h"

#include <mrpt/ros1bridge/map.h>
#include <mrpt/ros1bridge/pose.h>
#include <semnav/common/ClassRegistry.h>
#include <semnav/common/LabelSet.h>
#include <semnav/map/SemanticMap.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace semnav::ros1msg
{
namespace
{
std::vector<float> layerOrEmpty(const SemanticMap& map, const char* name)
{
	return map.exists(name) ? map.get(name) : std::vector<float>();
}

/** An empty grid with the map's geometry (every cell -1). */
nav_msgs::OccupancyGrid emptyGrid(
    const GridGeometry& g, const std_msgs::Header& header)
{
	nav_msgs::OccupancyGrid m;
	m.header = header;
	m.info.map_load_time = header.stamp;
	m.info.resolution = static_cast<float>(g.resolution);
	m.info.width = static_cast<uint32_t>(g.cols);
	m.info.height = static_cast<uint32_t>(g.rows);
	m.info.origin.position.x = g.originX;
	m.info.origin.position.y = g.originY;
	m.info.origin.orientation.w = 1;
	m.data.assign(g.cellCount(), -1);
	return m;
}

bool observed(const MapSnapshot& m, std::size_t i)
{
	return m.observations.empty() || m.observations[i] > 0;
}

std_msgs::ColorRGBA colourOf(Label l, float alpha)
{
	const auto c = classInfo(l).labelColour;
	std_msgs::ColorRGBA out;
	out.r = c.r / 255.0f;
	out.g = c.g / 255.0f;
	out.b = c.b / 255.0f;
	out.a = alpha;
	return out;
}

geometry_msgs::Quaternion yawQuaternion(double yaw)
{
	geometry_msgs::Quaternion q;
	q.z = std::sin(yaw / 2);
	q.w = std::cos(yaw / 2);
	return q;
}
}  // namespace

MapSnapshot snapshot(const SemanticMap& map)
{
	MapSnapshot s;
	mrpt::ros1bridge::toROS(map.occupancyGrid(), s.occupancy);
	s.geometry = map.geometry();
	s.labels = layerOrEmpty(map, "labels");
	s.cost = layerOrEmpty(map, "cost");
	s.observations = layerOrEmpty(map, "observations");
	// The bridge's cell table reads MRPT's free probability; semnav's grid
	// holds the occupancy probability: the cells are written here (-1 for a
	// cell never observed).
	const auto& g = s.geometry;
	auto& data = s.occupancy.data;
	if (data.size() == g.cellCount())
		for (int r = 0; r < g.rows; r++)
			for (int c = 0; c < g.cols; c++)
			{
				const std::size_t i = g.index(r, c);
				data[i] = observed(s, i) ? static_cast<int8_t>(std::lround(
				                               100 * map.occupancy(c, r)))
				                         : -1;
			}
	s.lethalCost = map.options().cost.lethalCost;
	s.instances = map.instances();
	return s;
}

nav_msgs::OccupancyGrid labelGrid(
    const MapSnapshot& m, Label label, const std_msgs::Header& header)
{
	auto grid = emptyGrid(m.geometry, header);
	if (m.labels.size() != grid.data.size()) return grid;
	for (std::size_t i = 0; i < grid.data.size(); i++)
		if (LabelSet(static_cast<LabelSet::mask_t>(m.labels[i]))
		        .contains(label))
			grid.data[i] = 100;
		else if (observed(m, i))
			grid.data[i] = 0;
	return grid;
}

nav_msgs::OccupancyGrid costGrid(
    const MapSnapshot& m, const std_msgs::Header& header)
{
	auto grid = emptyGrid(m.geometry, header);
	if (m.cost.size() != grid.data.size()) return grid;
	for (std::size_t i = 0; i < grid.data.size(); i++)
		if (observed(m, i))
			grid.data[i] = static_cast<int8_t>(std::clamp(
			    std::lround(100.0 * m.cost[i] / m.lethalCost), 0L, 100L));
	return grid;
}

visualization_msgs::MarkerArray objectMarkers(
    const std::vector<ObjectInstance>& instances,
    const std_msgs::Header& header)
{
	visualization_msgs::MarkerArray out;
	visualization_msgs::Marker clear;
	clear.header = header;
	clear.action = visualization_msgs::Marker::DELETEALL;
	out.markers.push_back(clear);
	for (const auto& o : instances)
	{
		visualization_msgs::Marker box;
		box.header = header;
		box.ns = "objects";
		box.id = o.id;
		box.type = visualization_msgs::Marker::CUBE;
		box.action = visualization_msgs::Marker::ADD;
		const auto size = o.maxCorner - o.minCorner;
		const bool bounded = size.x > 0 && size.y > 0 && size.z > 0;
		const auto centre =
		    bounded ? (o.minCorner + o.maxCorner) * 0.5 : o.centroid;
		box.pose.position.x = centre.x;
		box.pose.position.y = centre.y;
		box.pose.position.z = centre.z;
		box.pose.orientation.w = 1;
		box.scale.x = bounded ? size.x : 0.3;
		box.scale.y = bounded ? size.y : 0.3;
		box.scale.z = bounded ? size.z : 0.3;
		box.color = colourOf(o.label, 0.7f);
		out.markers.push_back(box);

		visualization_msgs::Marker text = box;
		text.ns = "labels";
		text.type = visualization_msgs::Marker::TEXT_VIEW_FACING;
		text.pose.position.z = centre.z + box.scale.z / 2 + 0.2;
		text.scale.x = text.scale.y = 0;
		text.scale.z = 0.25;
		text.color = colourOf(o.label, 1.0f);
		text.text = labelName(o.label) + " " + std::to_string(o.id) + " (" +
		            std::to_string(o.observations) + " obs)";
		out.markers.push_back(text);
	}
	return out;
}

nav_msgs::Path path(
    const SemanticNavigator::PlanRecord& plan, const std_msgs::Header& header)
{
	nav_msgs::Path out;
	out.header = header;
	for (std::size_t i = 0; i < plan.path.size(); i++)
	{
		const auto& p = plan.path[i];
		const auto& next = plan.path[std::min(i + 1, plan.path.size() - 1)];
		const auto& prev = plan.path[i > 0 ? i - 1 : 0];
		geometry_msgs::PoseStamped s;
		s.header = header;
		s.pose.position.x = p.x;
		s.pose.position.y = p.y;
		s.pose.orientation =
		    yawQuaternion(std::atan2(next.y - prev.y, next.x - prev.x));
		out.poses.push_back(s);
	}
	return out;
}

geometry_msgs::PoseWithCovarianceStamped pose(
    const mrpt::math::TPose2D& p, double stdXY, double stdYaw,
    const std_msgs::Header& header)
{
	geometry_msgs::PoseWithCovarianceStamped out;
	out.header = header;
	out.pose.pose.position.x = p.x;
	out.pose.pose.position.y = p.y;
	out.pose.pose.orientation = yawQuaternion(p.phi);
	out.pose.covariance[0] = out.pose.covariance[7] = stdXY * stdXY;
	out.pose.covariance[35] = stdYaw * stdYaw;
	return out;
}

tf2_msgs::TFMessage mapToOdom(
    const mrpt::math::TPose2D& pose, const mrpt::math::TPose2D& odometry,
    const std_msgs::Header& header, const std::string& odomFrame)
{
	// map <- odom = (map <- base) * (odom <- base)^-1
	mrpt::poses::CPose2D baseInOdom(odometry);
	baseInOdom.inverse();
	const auto t = (mrpt::poses::CPose2D(pose) + baseInOdom).asTPose();
	geometry_msgs::TransformStamped tf;
	tf.header = header;
	tf.child_frame_id = odomFrame;
	tf.transform.translation.x = t.x;
	tf.transform.translation.y = t.y;
	tf.transform.rotation = yawQuaternion(t.phi);
	tf2_msgs::TFMessage out;
	out.transforms.push_back(tf);
	return out;
}

sensor_msgs::PointCloud2 sweepCloud(
    const cv::Mat& points, const cv::Mat& labels, const mrpt::math::TPose2D& at,
    const std_msgs::Header& header)
{
	sensor_msgs::PointCloud2 out;
	out.header = header;
	out.height = 1;
	out.is_dense = true;
	out.is_bigendian = false;
	const char* names[] = {"x", "y", "z", "label"};
	for (uint32_t f = 0; f < 4; f++)
	{
		sensor_msgs::PointField field;
		field.name = names[f];
		field.offset = 4 * f;
		field.datatype = sensor_msgs::PointField::FLOAT32;
		field.count = 1;
		out.fields.push_back(field);
	}
	out.point_step = 16;
	const double c = std::cos(at.phi), s = std::sin(at.phi);
	std::vector<float> data;
	data.reserve(points.total() * 4);
	for (int r = 0; r < points.rows; r++)
		for (int col = 0; col < points.cols; col++)
		{
			const auto& p = points.at<cv::Vec3f>(r, col);
			if (!std::isfinite(p[0]) || !std::isfinite(p[1]) ||
			    !std::isfinite(p[2]))
				continue;
			data.push_back(static_cast<float>(at.x + c * p[0] - s * p[1]));
			data.push_back(static_cast<float>(at.y + s * p[0] + c * p[1]));
			data.push_back(p[2]);
			data.push_back(labels.empty() ? 0.0f : labels.at<uint8_t>(r, col));
		}
	out.width = static_cast<uint32_t>(data.size() / 4);
	out.row_step = out.point_step * out.width;
	out.data.resize(data.size() * sizeof(float));
	std::memcpy(out.data.data(), data.data(), out.data.size());
	return out;
}

}  // namespace semnav::ros1msg
