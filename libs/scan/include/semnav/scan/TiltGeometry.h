/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/math/TPoint3D.h>
#include <mrpt/poses/CPose3D.h>

namespace semnav
{
/** Pose, in the robot frame, of a 2D laser on a nodding head at tilt theta.
 *
 * The tilt axis is parallel to the robot's y axis and passes through `mount`.
 * Positive theta raises the beam at phi = 0, which in MRPT's yaw-pitch-roll
 * convention is pitch = -theta. `phiCenter` is the bearing of the scanner's
 * own x axis inside the scan plane (0 for a symmetric field of view such as
 * the LMS200's -90..90 deg); the beam at bearing phi then points along
 * (cos phi cos theta, sin phi, cos phi sin theta) for phiCenter = 0.
 * This is the `sensorPose` stored in each CObservation2DRangeScan of a
 * semnav rawlog. */
mrpt::poses::CPose3D tiltedSensorPose(
    const mrpt::math::TPoint3D& mount, double theta, double phiCenter = 0);

/** Inverse of tiltedSensorPose(): the tilt theta (rad) of a scan's
 * sensorPose, read from the direction of the sensor's z axis (independent
 * of phiCenter). */
double tiltOfSensorPose(const mrpt::poses::CPose3D& sensorPose);

}  // namespace semnav
