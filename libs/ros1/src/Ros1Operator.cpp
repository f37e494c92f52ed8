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

/** A latched topic built and sent only while someone listens: the worker
 * keeps the latest content and sends it when a subscriber is there (a late
 * subscriber gets it within one pass, as from latching). */
struct LatchedTopic
{
	ros::Publisher pub;
	/** Content newer than the last sent. */
	bool dirty = false;

	/** Publishes make() when dirty and listened to. */
	template <class Make>
	void publishIfListened(Make make)
	{
		if (!pub || !dirty || pub.getNumSubscribers() == 0) return;
		pub.publish(make());
		dirty = false;
	}
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
		mapTopic = latched<nav_msgs::OccupancyGrid>(o.mapTopic);
		costTopic = latched<nav_msgs::OccupancyGrid>(o.costTopic);
		if (!o.labelTopicPrefix.empty())
			for (const auto l : o.labelLayers)
				labelTopics.push_back(latched<nav_msgs::OccupancyGrid>(
				    o.labelTopicPrefix + "/" + labelName(l)));
		objectsTopic = latched<visualization_msgs::MarkerArray>(o.objectsTopic);
		pathTopic = latched<nav_msgs::Path>(o.pathTopic);
		sweepTopic = latched<sensor_msgs::PointCloud2>(o.sweepTopic);
		if (!o.poseTopic.empty())
			posePub = node.advertise<geometry_msgs::PoseWithCovarianceStamped>(
			    o.poseTopic, 10);
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

	template <class M>
	LatchedTopic latched(const std::string& topic)
	{
		LatchedTopic t;
		if (!topic.empty()) t.pub = node.advertise<M>(topic, 1, true);
		return t;
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

	/** Takes what the hooks left in the mailbox; publishes the pose, and
	 * the latched topics someone listens to. */
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
			stats.maps += m ? 1 : 0;
			stats.paths += p ? 1 : 0;
			stats.poses += pose ? 1 : 0;
			stats.sweeps += s ? 1 : 0;
		}
		if (m)
		{
			lastMap = std::move(m);
			mapStamp = ros::Time::now();
			for (auto* t : mapTopics()) t->dirty = true;
		}
		if (p)
		{
			lastPath = std::move(p);
			pathTopic.dirty = true;
		}
		if (s)
		{
			lastSweep = std::move(s);
			sweepTopic.dirty = true;
		}
		if (pose) publishPose(*pose, sxy, syaw);
		publishListened();
	}

	std::vector<LatchedTopic*> mapTopics()
	{
		std::vector<LatchedTopic*> out{&mapTopic, &costTopic, &objectsTopic};
		for (auto& t : labelTopics) out.push_back(&t);
		return out;
	}

	void publishListened()
	{
		if (lastMap)
		{
			const auto& m = *lastMap;
			const auto h = header(mapStamp);
			mapTopic.publishIfListened(
			    [&]
			    {
				    auto g = m.occupancy;
				    g.header = h;
				    g.info.map_load_time = h.stamp;
				    return g;
			    });
			for (std::size_t i = 0; i < labelTopics.size(); i++)
				labelTopics[i].publishIfListened(
				    [&] {
					    return ros1msg::labelGrid(m, options.labelLayers[i], h);
				    });
			costTopic.publishIfListened([&]
			                            { return ros1msg::costGrid(m, h); });
			objectsTopic.publishIfListened(
			    [&] { return ros1msg::objectMarkers(m.instances, h); });
		}
		if (lastPath) pathTopic.publishIfListened([&] { return *lastPath; });
		if (lastSweep)
			sweepTopic.publishIfListened(
			    [&]
			    {
				    return ros1msg::sweepCloud(
				        lastSweep->points, lastSweep->labels, lastSweep->at,
				        header());
			    });
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
	LatchedTopic mapTopic, costTopic, objectsTopic, pathTopic, sweepTopic;
	std::vector<LatchedTopic> labelTopics;
	ros::Publisher posePub, tfPub;
	/** The worker's latest map, plan and sweep. */
	std::optional<ros1msg::MapSnapshot> lastMap;
	ros::Time mapStamp;
	std::optional<nav_msgs::Path> lastPath;
	std::optional<SweepCopy> lastSweep;
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
	SteadyClock::time_point lastMapTaken, lastPoseTaken;
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
	if (now - m_impl->lastMapTaken <
	    std::chrono::duration<double>(m_impl->options.mapPeriod))
		return false;
	m_impl->lastMapTaken = now;
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
	if (now - m_impl->lastPoseTaken <
	    std::chrono::duration<double>(1.0 / m_impl->options.poseRate))
		return;
	m_impl->lastPoseTaken = now;
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
