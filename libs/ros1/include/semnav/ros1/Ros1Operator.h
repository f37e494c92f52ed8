/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/ros1/Ros1OperatorOptions.h>
#include <semnav/runtime/RobotSessionObserver.h>

#include <cstddef>
#include <functional>
#include <memory>
#include <string>

namespace semnav
{
/** semnav-robot for ROS 1 operators (rviz, move_base costmaps): observes a
 * RobotSession and publishes, under the names of [Ros1Operator]:
 * - the map's occupancy (nav_msgs/OccupancyGrid through mrpt-ros1bridge),
 *   one grid per label layer and the travel cost u as a 0-100 grid, all
 *   latched and republished when the map changes (at most every
 *   map_period_s);
 * - the object instances (visualization_msgs/MarkerArray: a box of each
 *   instance's extent, and its label, id and observation count as text);
 * - the current plan (nav_msgs/Path), the pose estimate
 *   (geometry_msgs/PoseWithCovarianceStamped, the covariance of the last
 *   localized sweep) and tf map -> odom (tf2_msgs/TFMessage on /tf);
 * - the last sweep (sensor_msgs/PointCloud2 in the map frame, fields x y z
 *   label, the label's numeric id).
 *
 * Pose goals (geometry_msgs/PoseStamped in the map frame, as rviz's 2D Nav
 * Goal sends them) become "go to x y" command lines for `onCommand`; a
 * goal it cannot take goes to `onError` (the goal, why).
 *
 * The hooks only copy what changed into a mailbox (the map when its
 * version changed); converting and publishing happen on this object's own
 * thread, so the control loop is never held up by ROS. The latched topics
 * are built only while someone subscribes (a late subscriber gets the
 * latest within one pass, 20 ms). Starts roscpp when
 * needed (startRosNode; IoError when the master does not answer). */
class Ros1Operator : public RobotSessionObserver
{
public:
	using TOptions = Ros1OperatorOptions;
	using CommandSink = std::function<void(const std::string& line)>;
	using ErrorSink = std::function<void(
	    const std::string& command, const std::string& error)>;

	/** Map versions, plans, poses and sweeps taken from the session so
	 * far, goals received, and the longest a hook held the control loop
	 * (ms). */
	struct Stats
	{
		std::size_t maps = 0, paths = 0, poses = 0, sweeps = 0, goals = 0;
		double maxHookMs = 0;
	};

	Ros1Operator(
	    const std::string& nodeName, double masterTimeout,
	    const TOptions& options, CommandSink onCommand, ErrorSink onError);
	~Ros1Operator() override;
	Ros1Operator(const Ros1Operator&) = delete;
	Ros1Operator& operator=(const Ros1Operator&) = delete;

	bool onMapChanged(const SemanticMap& map) override;
	void onPlan(const SemanticNavigator::PlanRecord& plan) override;
	void onPose(
	    const mrpt::math::TPose2D& pose, const mrpt::math::TPose2D& odometry,
	    mrpt::Clock::time_point odometryTime) override;
	void onSweep(
	    const Sweep& sweep, const LabeledSweep& labeled,
	    const mrpt::math::TPose2D& estimate, double stdXY,
	    double stdYaw) override;

	Stats stats() const;

private:
	struct Impl;
	std::unique_ptr<Impl> m_impl;
};

}  // namespace semnav
