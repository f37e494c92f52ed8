/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <semnav/scan/TiltGeometry.h>

#include <cmath>

namespace semnav::test
{
/** Range of beam `c` on a synthetic line at tilt index `k`: unique per pixel
 * so tests can check where every value went. */
inline float syntheticRange(int k, std::size_t c)
{
	return 1.0f + 0.01f * k + 0.001f * c;
}

/** A 2D scan line at tilt index k (theta = thetaMin + k * step). */
inline mrpt::obs::CObservation2DRangeScan::Ptr makeLine(
    int k, double thetaMin = -15 * M_PI / 180, double step = 0.5 * M_PI / 180,
    std::size_t beams = 361, const std::string& label = "TILT_LMS")
{
	auto s = mrpt::obs::CObservation2DRangeScan::Create();
	s->sensorLabel = label;
	s->aperture = static_cast<float>(M_PI);
	s->rightToLeft = true;
	s->maxRange = 8.0f;
	s->resizeScan(beams);
	for (std::size_t c = 0; c < beams; c++)
	{
		s->setScanRange(c, syntheticRange(k, c));
		s->setScanRangeValidity(c, (c % 50) != 7);
	}
	s->sensorPose = tiltedSensorPose({0, 0, 0.45}, thetaMin + k * step);
	s->timestamp = mrpt::Clock::fromDouble(1.0e9 + 0.03 * k);
	return s;
}

inline mrpt::obs::CObservationOdometry::Ptr makeOdometry(
    double x, double y, double yaw)
{
	auto o = mrpt::obs::CObservationOdometry::Create();
	o->sensorLabel = "ODOMETRY";
	o->odometry = mrpt::poses::CPose2D(x, y, yaw);
	return o;
}

}  // namespace semnav::test
