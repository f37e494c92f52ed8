/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/poses/CPose3D.h>
#include <ros/time.h>
#include <sensor_msgs/LaserScan.h>

#include <string>

namespace semnav
{
/** Time of a scan's middle beam: header.stamp (the first beam, or
 * `fallback` when the stamp is zero) + (n - 1) / 2 * time_increment. The
 * tilt of the line is taken at this time. */
ros::Time scanMidTime(
    const sensor_msgs::LaserScan& msg, const ros::Time& fallback);

/** A LaserScan as one semnav scan line (docs/design.md, "Rawlog"): beams
 * by increasing angle (a clockwise scan is reversed), aperture |angle_max -
 * angle_min| (or (n - 1) |angle_increment| when they disagree by half a
 * step or more), sensorPose = `headPose` turned by the scan's centre
 * bearing, a beam valid when finite and within [range_min, range_max]
 * (REP 117), an invalid one storing range_max. Stamped `stamp`. Returns ""
 * or why the message cannot be a line. */
std::string toScanLine(
    const sensor_msgs::LaserScan& msg, const mrpt::poses::CPose3D& headPose,
    const ros::Time& stamp, const std::string& sensorLabel,
    mrpt::obs::CObservation2DRangeScan& out);

}  // namespace semnav
