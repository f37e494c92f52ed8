/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/math/wrap2pi.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/ros1bridge/pose.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <semnav/common/Error.h>
#include <semnav/ros1/BagToRawlog.h>
#include <semnav/scan/RawlogWriter.h>
#include <semnav/scan/TiltGeometry.h>
#include <sensor_msgs/JointState.h>
#include <sensor_msgs/LaserScan.h>
#include <tf2/buffer_core.h>
#include <tf2/exceptions.h>
#include <tf2_msgs/TFMessage.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <set>

#include "LaserScanLine.h"
#include "TimedSamples.h"

namespace semnav
{
namespace
{
const std::string kLaserScan = "sensor_msgs/LaserScan";
const std::string kJointState = "sensor_msgs/JointState";
const std::string kOdometry = "nav_msgs/Odometry";
const std::string kTfMessage = "tf2_msgs/TFMessage";
const std::vector<std::string> kTfTopics = {"/tf", "/tf_static"};

/** topic -> message type of every connection of a bag. */
using TopicTypes = std::map<std::string, std::string>;

std::string listed(const TopicTypes& topics)
{
	if (topics.empty()) return "none";
	std::string s;
	for (const auto& [topic, type] : topics)
		s += (s.empty() ? "" : ", ") + topic + " (" + type + ")";
	return s;
}

std::string listed(const std::set<std::string>& names)
{
	if (names.empty()) return "none";
	std::string s;
	for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
	return s;
}

/** First line of an exception message (tf2's run over several). */
std::string firstLine(const std::string& s)
{
	return s.substr(0, s.find('\n'));
}

ros::Time stampOf(const std_msgs::Header& h, const rosbag::MessageInstance& m)
{
	return h.stamp.isZero() ? m.getTime() : h.stamp;
}

mrpt::poses::CPose3D poseOf(const geometry_msgs::Transform& t)
{
	geometry_msgs::Pose p;
	p.position.x = t.translation.x;
	p.position.y = t.translation.y;
	p.position.z = t.translation.z;
	p.orientation = t.rotation;
	return mrpt::ros1bridge::fromROS(p);
}

/** Odometry readings this close are one (tf's interpolation between equal
 * transforms is not exact). */
bool samePose(const mrpt::poses::CPose2D& a, const mrpt::poses::CPose2D& b)
{
	constexpr double kEpsilon = 1e-6;  // m, rad
	return std::abs(a.x() - b.x()) < kEpsilon &&
	       std::abs(a.y() - b.y()) < kEpsilon &&
	       std::abs(mrpt::math::wrapToPi(a.phi() - b.phi())) < kEpsilon;
}

/** The tilt, odometry and tf messages of a bag (first pass). */
struct BagInputs
{
	TimedSamples<double> tilt;
	TimedSamples<mrpt::poses::CPose2D> odometry;
	std::unique_ptr<tf2::BufferCore> tf;
	std::set<std::string> joints;
};

/** One conversion: the open bag, its first pass and the rawlog. */
class BagConversion
{
public:
	BagConversion(const BagToRawlog::TOptions& o, const std::string& bagPath)
	    : m_o(o), m_path(bagPath)
	{
		try
		{
			m_bag.open(bagPath, rosbag::bagmode::Read);
		}
		catch (const std::exception& e)
		{
			throw IoError("cannot read bag " + bagPath + ": " + e.what());
		}
		rosbag::View all(m_bag);
		for (const auto* c : all.getConnections())
			m_topics[c->topic] = c->datatype;
		checkTopics();
	}

	BagToRawlog::Result run(
	    const std::string& rawlogPath,
	    const BagToRawlog::ProgressCallback& progress)
	{
		try
		{
			readInputs();
			return writeRawlog(rawlogPath, progress);
		}
		catch (const rosbag::BagException& e)
		{
			throw IoError("cannot read bag " + m_path + ": " + e.what());
		}
	}

private:
	void requireTopic(
	    const std::string& topic, const std::string& type,
	    const std::string& hint) const
	{
		const auto it = m_topics.find(topic);
		if (it == m_topics.end())
			throw Error(
			    "bag " + m_path + " has no topic " + topic + " (" + type +
			    "; " + hint + "); its topics: " + listed(m_topics));
		if (it->second != type)
			throw Error(
			    "topic " + topic + " of bag " + m_path + " is " + it->second +
			    ", expected " + type + " (" + hint + ")");
	}

	void checkTopics() const
	{
		using S = BagToRawlog::Source;
		requireTopic(m_o.scanTopic, kLaserScan, "--scan-topic");
		if (m_o.tiltFrom == S::Topic)
			requireTopic(
			    m_o.jointStatesTopic, kJointState,
			    "--joint-states-topic, or --tilt-from tf");
		if (m_o.odomFrom == S::Topic)
			requireTopic(
			    m_o.odomTopic, kOdometry, "--odom-topic, or --odom-from tf");
		if (usesTf() && !m_topics.count("/tf") && !m_topics.count("/tf_static"))
			requireTopic("/tf", kTfMessage, "tilt or odometry from tf");
	}

	bool usesTf() const
	{
		return m_o.tiltFrom == BagToRawlog::Source::Tf ||
		       m_o.odomFrom == BagToRawlog::Source::Tf;
	}

	/** First pass: tilt samples, odometry readings and tf. */
	void readInputs()
	{
		using S = BagToRawlog::Source;
		std::vector<std::string> topics;
		if (m_o.tiltFrom == S::Topic) topics.push_back(m_o.jointStatesTopic);
		if (m_o.odomFrom == S::Topic) topics.push_back(m_o.odomTopic);
		if (usesTf())
		{
			for (const auto& t : kTfTopics)
				if (m_topics.count(t)) topics.push_back(t);
			rosbag::View span(m_bag);
			const double seconds =
			    (span.getEndTime() - span.getBeginTime()).toSec();
			m_in.tf =
			    std::make_unique<tf2::BufferCore>(ros::Duration(seconds + 10));
		}
		const double sign = m_o.tiltAxisNegative ? 1 : -1;
		rosbag::View view(m_bag, rosbag::TopicQuery(topics));
		for (const rosbag::MessageInstance& m : view)
		{
			if (m.getTopic() == m_o.jointStatesTopic &&
			    m_o.tiltFrom == S::Topic)
			{
				const auto js = m.instantiate<sensor_msgs::JointState>();
				if (!js) continue;
				for (std::size_t i = 0; i < js->name.size(); i++)
				{
					m_in.joints.insert(js->name[i]);
					if (js->name[i] == m_o.tiltJoint && i < js->position.size())
						m_in.tilt.add(
						    stampOf(js->header, m),
						    sign * js->position[i] + m_o.tiltOffset);
				}
			}
			else if (m.getTopic() == m_o.odomTopic && m_o.odomFrom == S::Topic)
			{
				const auto od = m.instantiate<nav_msgs::Odometry>();
				if (!od) continue;
				m_in.odometry.add(
				    stampOf(od->header, m),
				    mrpt::poses::CPose2D(
				        mrpt::ros1bridge::fromROS(od->pose.pose)));
			}
			else if (const auto tf = m.instantiate<tf2_msgs::TFMessage>())
			{
				const bool isStatic = m.getTopic() == "/tf_static";
				for (const auto& t : tf->transforms)
					m_in.tf->setTransform(t, "bag", isStatic);
			}
		}
		m_in.tilt.sort();
		m_in.odometry.sort();
		checkInputs();
	}

	void requireFrame(const std::string& frame, const std::string& option) const
	{
		if (m_in.tf->_frameExists(frame)) return;
		std::vector<std::string> ids;
		m_in.tf->_getFrameStrings(ids);
		const std::set<std::string> frames(ids.begin(), ids.end());
		throw Error(
		    "bag " + m_path + " has no tf frame '" + frame + "' (" + option +
		    "); its frames: " + listed(frames));
	}

	void checkInputs() const
	{
		using S = BagToRawlog::Source;
		if (m_o.tiltFrom == S::Topic && m_in.tilt.empty())
			throw Error(
			    "joint '" + m_o.tiltJoint + "' is not in " +
			    m_o.jointStatesTopic + " of bag " + m_path +
			    " (--tilt-joint); its joints: " + listed(m_in.joints));
		if (m_o.odomFrom == S::Topic && m_in.odometry.empty())
			throw Error(
			    "topic " + m_o.odomTopic + " of bag " + m_path +
			    " has no message (--odom-topic)");
		if (usesTf()) requireFrame(m_o.baseFrame, "--base-frame");
		if (m_o.tiltFrom == S::Tf && !m_o.laserFrame.empty())
			requireFrame(m_o.laserFrame, "--laser-frame");
		if (m_o.odomFrom == S::Tf) requireFrame(m_o.odomFrame, "--odom-frame");
	}

	/** The head's pose (tilt, no scan centre) in the base frame at t. */
	std::optional<mrpt::poses::CPose3D> headPose(
	    const ros::Time& t, const std::string& scanFrame, std::string& why)
	{
		if (m_o.tiltFrom == BagToRawlog::Source::Tf)
		{
			const std::string& laser =
			    m_o.laserFrame.empty() ? scanFrame : m_o.laserFrame;
			if (!m_laserFrameChecked)
			{
				requireFrame(laser, "--laser-frame, or the scans' frame_id");
				m_laserFrameChecked = true;
			}
			return lookup(m_o.baseFrame, laser, t, why);
		}
		const auto* a = m_in.tilt.atOrBefore(t);
		const auto* b = m_in.tilt.atOrAfter(t);
		if (!a || !b)
		{
			why = "no " + m_o.tiltJoint + " position " +
			      (a ? "after" : "before") + " the line";
			return std::nullopt;
		}
		const double gap = (b->stamp - a->stamp).toSec();
		if (gap > m_o.maxGap)
		{
			why = "the " + m_o.tiltJoint + " positions around the line are " +
			      std::to_string(gap) + " s apart (--max-gap)";
			return std::nullopt;
		}
		const double k = gap > 0 ? (t - a->stamp).toSec() / gap : 0;
		const double theta = a->value + k * (b->value - a->value);
		return tiltedSensorPose(m_o.mount, theta);
	}

	std::optional<mrpt::poses::CPose2D> odometryAt(
	    const ros::Time& t, std::string& why)
	{
		if (m_o.odomFrom == BagToRawlog::Source::Tf)
		{
			const auto p = lookup(m_o.odomFrame, m_o.baseFrame, t, why);
			if (!p) return std::nullopt;
			return mrpt::poses::CPose2D(*p);
		}
		const auto* a = m_in.odometry.atOrBefore(t);
		if (!a)
		{
			why = "no " + m_o.odomTopic + " message before the line";
			return std::nullopt;
		}
		const double age = (t - a->stamp).toSec();
		if (age > m_o.maxGap)
		{
			why = "the last " + m_o.odomTopic + " message is " +
			      std::to_string(age) + " s older than the line (--max-gap)";
			return std::nullopt;
		}
		return a->value;
	}

	std::optional<mrpt::poses::CPose3D> lookup(
	    const std::string& target, const std::string& source,
	    const ros::Time& t, std::string& why) const
	{
		try
		{
			return poseOf(
			    m_in.tf->lookupTransform(target, source, t).transform);
		}
		catch (const tf2::TransformException& e)
		{
			why = "tf " + target + " -> " + source + ": " + firstLine(e.what());
			return std::nullopt;
		}
	}

	void skip(
	    std::size_t& counter, const std::string& why, const ros::Time& t,
	    BagToRawlog::Result& r) const
	{
		counter++;
		if (r.firstSkip.empty())
		{
			char stamp[32];
			std::snprintf(stamp, sizeof(stamp), "%.3f", t.toSec());
			r.firstSkip = "line at " + std::string(stamp) + ": " + why;
		}
	}

	/** Second pass: the scans, with the odometry before them. */
	BagToRawlog::Result writeRawlog(
	    const std::string& rawlogPath,
	    const BagToRawlog::ProgressCallback& progress)
	{
		BagToRawlog::Result r;
		RawlogWriter out(rawlogPath);
		rosbag::View view(m_bag, rosbag::TopicQuery(m_o.scanTopic));
		const std::size_t total = view.size();
		std::optional<mrpt::poses::CPose2D> lastOdometry;
		mrpt::obs::CObservation2DRangeScan line;
		for (const rosbag::MessageInstance& m : view)
		{
			r.scans++;
			if (progress) progress(r.scans, total);
			const auto scan = m.instantiate<sensor_msgs::LaserScan>();
			if (!scan) continue;
			const ros::Time t = scanMidTime(*scan, m.getTime());
			std::string why;
			const auto head = headPose(t, scan->header.frame_id, why);
			if (!head)
			{
				skip(r.skippedNoTilt, why, t, r);
				continue;
			}
			const auto odometry = odometryAt(t, why);
			if (!odometry)
			{
				skip(r.skippedNoOdometry, why, t, r);
				continue;
			}
			why = toScanLine(*scan, *head, t, m_o.sensorLabel, line);
			if (!why.empty())
			{
				skip(r.skippedBadScan, why, t, r);
				continue;
			}
			if (!lastOdometry || !samePose(*lastOdometry, *odometry))
			{
				mrpt::obs::CObservationOdometry o;
				o.sensorLabel = "ODOMETRY";
				o.timestamp = line.timestamp;
				o.odometry = *odometry;
				out.write(o);
				r.odometry++;
				lastOdometry = odometry;
			}
			out.write(line);
			if (r.lines == 0) r.firstStamp = t.toSec();
			r.lastStamp = t.toSec();
			r.lines++;
		}
		if (r.lines == 0)
			throw Error(
			    "no scan line of " + m_o.scanTopic + " in bag " + m_path +
			    " could be converted (" + std::to_string(r.scans) +
			    " scans; first: " +
			    (r.firstSkip.empty() ? "none" : r.firstSkip) + ")");
		out.commit();
		return r;
	}

	const BagToRawlog::TOptions& m_o;
	std::string m_path;
	rosbag::Bag m_bag;
	TopicTypes m_topics;
	BagInputs m_in;
	bool m_laserFrameChecked = false;
};

}  // namespace

BagToRawlog::BagToRawlog(const TOptions& options) : m_options(options) {}

BagToRawlog::Result BagToRawlog::convert(
    const std::string& bagPath, const std::string& rawlogPath,
    const ProgressCallback& progress)
{
	if (!ros::Time::isValid()) ros::Time::init();
	BagConversion conversion(m_options, bagPath);
	return conversion.run(rawlogPath, progress);
}

}  // namespace semnav
