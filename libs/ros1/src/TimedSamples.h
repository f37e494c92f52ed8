/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <ros/time.h>

#include <algorithm>
#include <vector>

namespace semnav
{
/** Values stamped with ROS times (tilt angles, odometry readings of a
 * bag), looked up by time. Add all samples, sort() once, then look up. */
template <typename T>
class TimedSamples
{
public:
	struct Sample
	{
		ros::Time stamp;
		T value;
	};

	void add(const ros::Time& stamp, const T& value)
	{
		m_samples.push_back({stamp, value});
	}
	/** Orders the samples by stamp (bag order may differ); equal stamps
	 * keep their bag order. */
	void sort()
	{
		std::stable_sort(
		    m_samples.begin(), m_samples.end(),
		    [](const Sample& a, const Sample& b) { return a.stamp < b.stamp; });
	}

	bool empty() const { return m_samples.empty(); }
	std::size_t size() const { return m_samples.size(); }

	/** The last sample stamped at or before t; nullptr when none is. */
	const Sample* atOrBefore(const ros::Time& t) const
	{
		auto it = std::upper_bound(
		    m_samples.begin(), m_samples.end(), t,
		    [](const ros::Time& u, const Sample& s) { return u < s.stamp; });
		return it == m_samples.begin() ? nullptr : &*(it - 1);
	}
	/** The first sample stamped at or after t; nullptr when none is. */
	const Sample* atOrAfter(const ros::Time& t) const
	{
		auto it = std::lower_bound(
		    m_samples.begin(), m_samples.end(), t,
		    [](const Sample& s, const ros::Time& u) { return s.stamp < u; });
		return it == m_samples.end() ? nullptr : &*it;
	}

private:
	std::vector<Sample> m_samples;
};

}  // namespace semnav
