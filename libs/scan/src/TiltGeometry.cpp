/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/scan/TiltGeometry.h>

#include <cmath>

namespace semnav
{
mrpt::poses::CPose3D tiltedSensorPose(
    const mrpt::math::TPoint3D& mount, double theta, double phiCenter)
{
	// MRPT pitch is positive nose-down, so a head raised by theta has
	// pitch = -theta. The scanner's own yaw inside the scan plane comes last.
	const mrpt::poses::CPose3D head(mount.x, mount.y, mount.z, 0, -theta, 0);
	if (phiCenter == 0) return head;
	return head + mrpt::poses::CPose3D(0, 0, 0, phiCenter, 0, 0);
}

double tiltOfSensorPose(const mrpt::poses::CPose3D& sensorPose)
{
	// The scanner's z axis is (-sin theta, 0, cos theta) in the robot frame.
	const auto& R = sensorPose.getRotationMatrix();
	return std::atan2(-R(0, 2), R(2, 2));
}

}  // namespace semnav
