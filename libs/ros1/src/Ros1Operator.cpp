/* semnav: semantic navigation from tilting-laser sweeps */
#include <geometry_msgs/PoseStamped.h>
#include <mrpt/core/format.h>
#include <mrpt/ros1bridge/time.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <semnav/perception/LabeledSweep.h>
#include <semnav/ros1/Ros1Operator.h>
#include <semnav/ros1/RosNode.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <optional>
#include <thread>

#include "Ros1OperatorMessages.h"

namespace semnav
{
namespace
{
using SteadyClock = std::chrono::steady_clock;

/** A sweep's points and labels, with where it was taken. */
struct SweepCopy
{
	cv::Mat points, labels;
	mrpt::math::TPose2D at;
};

struct PoseState
{
	mrpt::math::TPose2D pose, odometry;
	mrpt::Clock::time_point odometryTime;
};

/** Records the time from construction to destruction into `maxMs` (the
 * longest so far) under `mutex`. */
class HookTimer
{
public:
	HookTimer(std::mutex& mutex, double& maxMs) : m_mutex(mutex), m_max(maxMs)
	{
	}
	~HookTimer()
	{
		const double ms = std::chrono::duration<double, std::milli>(
		                      SteadyClock::now() - m_start)
		                      .count();
		std::lock_guard<std::mutex> lk(m_mutex);
		m_max = std::max(m_max, ms);
	}

private:
	std::mutex& m_mutex;
	double& m_max;
	const SteadyClock::time_point m_start = SteadyClock::now();
};

std::string withoutSlash(const std::string& frame)
{
	return !frame.empty() && frame[0] == '/' ? frame.substr(1) : frame;
}
}  // namespace

struct Ros1Operator::Impl
{
	Impl(const TOptions& o, CommandSink command, ErrorSink error)
	    : options(o), onCommand(std::move(command)), onError(std::move(error))
	{
		node.setCallbackQueue(&queue);
		const auto latched = [&](const std::string& topic)
		{
			return topic.empty() ? ros::Publisher()
			                     : node.advertise<nav_msgs::OccupancyGrid>(
			                           topic, 1, true);
		};
		mapPub = latched(o.mapTopic);
		costPub = latched(o.costTopic);
		if (!o.labelTopicPrefix.empty())
			for (const auto l : o.labelLayers)
				labelPubs.push_back(
				    latched(o.labelTopicPrefix + "/" + labelName(l)));
		if (!o.objectsTopic.empty())
			objectsPub = node.advertise<visualization_msgs::MarkerArray>(
			    o.objectsTopic, 1, true);
		if (!o.pathTopic.empty())
			pathPub = node.advertise<nav_msgs::Path>(o.pathTopic, 1, true);
		if (!o.poseTopic.empty())
			posePub = node.advertise<geometry_msgs::PoseWithCovarianceStamped>(
			    o.poseTopic, 10);
		if (!o.sweepTopic.empty())
			sweepPub =
			    node.advertise<sensor_msgs::PointCloud2>(o.sweepTopic, 1, true);
		if (o.publishTf) tfPub = node.advertise<tf2_msgs::TFMessage>("/tf", 10);
		if (!o.goalTopic.empty())
			goalSub = node.subscribe(o.goalTopic, 10, &Impl::onGoal, this);
		thread = std::thread([this] { run(); });
	}

	~Impl()
	{
		running = false;
		thread.join();
	}

	std_msgs::Header header(ros::Time stamp = ros::Time::now()) const
	{
		std_msgs::Header h;
		h.stamp = stamp;
		h.frame_id = options.mapFrame;
		return h;
	}

	void onGoal(const geometry_msgs::PoseStamped::ConstPtr& g)
	{
		const auto& p = g->pose.position;
		const std::string what = mrpt::format(
		    "%s goal (%g, %g) in frame '%s'", options.goalTopic.c_str(), p.x,
		    p.y, g->header.frame_id.c_str());
		const std::string frame = withoutSlash(g->header.frame_id);
		if (!frame.empty() && frame != withoutSlash(options.mapFrame))
			onError(
			    what,
			    "goals must be in the map frame '" + options.mapFrame + "'");
		else if (!std::isfinite(p.x) || !std::isfinite(p.y))
			onError(what, "the goal is not a finite position");
		else
		{
			onCommand(mrpt::format("go to %.3f %.3f", p.x, p.y));
			std::lock_guard<std::mutex> lk(mutex);
			stats.goals++;
		}
	}

	/** Publishes what the hooks left in the mailbox. */
	void publishPending()
	{
		std::optional<ros1msg::MapSnapshot> m;
		std::optional<nav_msgs::Path> p;
		std::optional<PoseState> pose;
		std::optional<SweepCopy> s;
		double sxy, syaw;
		{
			std::lock_guard<std::mutex> lk(mutex);
			m.swap(map);
			p.swap(path);
			pose.swap(latestPose);
			s.swap(sweep);
			sxy = stdXY;
			syaw = stdYaw;
		}
		if (m) publishMap(*m);
		if (p && pathPub) pathPub.publish(*p);
		if (pose) publishPose(*pose, sxy, syaw);
		if (s && sweepPub)
			sweepPub.publish(
			    ros1msg::sweepCloud(s->points, s->labels, s->at, header()));
		std::lock_guard<std::mutex> lk(mutex);
		stats.maps += m ? 1 : 0;
		stats.paths += p ? 1 : 0;
		stats.poses += pose ? 1 : 0;
		stats.sweeps += s ? 1 : 0;
	}

	void publishMap(ros1msg::MapSnapshot& m)
	{
		const auto h = header();
		if (mapPub)
		{
			m.occupancy.header = h;
			m.occupancy.info.map_load_time = h.stamp;
			mapPub.publish(m.occupancy);
		}
		for (std::size_t i = 0; i < labelPubs.size(); i++)
			labelPubs[i].publish(
			    ros1msg::labelGrid(m, options.labelLayers[i], h));
		if (costPub) costPub.publish(ros1msg::costGrid(m, h));
		if (objectsPub)
			objectsPub.publish(ros1msg::objectMarkers(m.instances, h));
	}

	void publishPose(const PoseState& p, double sxy, double syaw)
	{
		if (posePub)
			posePub.publish(ros1msg::pose(p.pose, sxy, syaw, header()));
		if (!tfPub) return;
		const auto stamp = p.odometryTime == mrpt::Clock::time_point{}
		                       ? ros::Time::now()
		                       : mrpt::ros1bridge::toROS(p.odometryTime);
		tfPub.publish(ros1msg::mapToOdom(
		    p.pose, p.odometry, header(stamp), options.odomFrame));
	}

	void run()
	{
		while (running)
		{
			queue.callAvailable(ros::WallDuration(0.02));
			publishPending();
		}
	}

	const TOptions options;
	CommandSink onCommand;
	ErrorSink onError;
	ros::CallbackQueue queue;
	ros::NodeHandle node;
	ros::Publisher mapPub, costPub, objectsPub, pathPub, posePub, sweepPub,
	    tfPub;
	std::vector<ros::Publisher> labelPubs;
	ros::Subscriber goalSub;
	std::thread thread;
	std::atomic<bool> running{true};

	/** The mailbox (latest of each kind) and the counters. */
	mutable std::mutex mutex;
	std::optional<ros1msg::MapSnapshot> map;
	std::optional<nav_msgs::Path> path;
	std::optional<PoseState> latestPose;
	std::optional<SweepCopy> sweep;
	double stdXY = 0, stdYaw = 0;
	Stats stats;
	/** Control thread only. */
	SteadyClock::time_point lastMap, lastPose;
};

Ros1Operator::Ros1Operator(
    const std::string& nodeName, double masterTimeout, const TOptions& options,
    CommandSink onCommand, ErrorSink onError)
{
	startRosNode(nodeName, masterTimeout);
	m_impl = std::make_unique<Impl>(
	    options, std::move(onCommand), std::move(onError));
}

Ros1Operator::~Ros1Operator() = default;

bool Ros1Operator::onMapChanged(const SemanticMap& map)
{
	const HookTimer timer(m_impl->mutex, m_impl->stats.maxHookMs);
	const auto now = SteadyClock::now();
	if (now - m_impl->lastMap <
	    std::chrono::duration<double>(m_impl->options.mapPeriod))
		return false;
	m_impl->lastMap = now;
	auto s = ros1msg::snapshot(map);
	std::lock_guard<std::mutex> lk(m_impl->mutex);
	m_impl->map = std::move(s);
	return true;
}

void Ros1Operator::onPlan(const SemanticNavigator::PlanRecord& plan)
{
	const HookTimer timer(m_impl->mutex, m_impl->stats.maxHookMs);
	if (m_impl->options.pathTopic.empty()) return;
	auto p = ros1msg::path(plan, m_impl->header());
	std::lock_guard<std::mutex> lk(m_impl->mutex);
	m_impl->path = std::move(p);
}

void Ros1Operator::onPose(
    const mrpt::math::TPose2D& pose, const mrpt::math::TPose2D& odometry,
    mrpt::Clock::time_point odometryTime)
{
	const HookTimer timer(m_impl->mutex, m_impl->stats.maxHookMs);
	const auto now = SteadyClock::now();
	if (now - m_impl->lastPose <
	    std::chrono::duration<double>(1.0 / m_impl->options.poseRate))
		return;
	m_impl->lastPose = now;
	std::lock_guard<std::mutex> lk(m_impl->mutex);
	m_impl->latestPose = PoseState{pose, odometry, odometryTime};
}

void Ros1Operator::onSweep(
    const Sweep&, const LabeledSweep& labeled,
    const mrpt::math::TPose2D& estimate, double stdXY, double stdYaw)
{
	const HookTimer timer(m_impl->mutex, m_impl->stats.maxHookMs);
	std::optional<SweepCopy> s;
	if (!m_impl->options.sweepTopic.empty())
		s = SweepCopy{labeled.points.clone(), labeled.labels.clone(), estimate};
	std::lock_guard<std::mutex> lk(m_impl->mutex);
	if (s) m_impl->sweep = std::move(s);
	m_impl->stdXY = stdXY;
	m_impl->stdYaw = stdYaw;
}

Ros1Operator::Stats Ros1Operator::stats() const
{
	std::lock_guard<std::mutex> lk(m_impl->mutex);
	return m_impl->stats;
}

}  // namespace semnav
