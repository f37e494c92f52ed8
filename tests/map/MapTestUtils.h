/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/perception/LabeledSweep.h>
#include <semnav/scan/Sweep.h>
#include <semnav/scan/TiltGeometry.h>

#include <cmath>
#include <vector>

namespace semnav::test
{
/** A hand-made classified sweep: one row of robot-frame points with labels
 * (what PerceptionPipeline would output), and the matching 1-row Sweep
 * whose sensor sits at height 0.45 m. */
struct FakeSweep
{
	Sweep sweep;
	LabeledSweep labeled;
};

struct FakePoint
{
	double x, y, z;
	Label label;
};

inline FakeSweep makeFakeSweep(const std::vector<FakePoint>& pts)
{
	FakeSweep f;
	const int n = static_cast<int>(pts.size());
	f.sweep = Sweep(1, pts.size());
	f.sweep.setRow(0, 0.0, tiltedSensorPose({0, 0, 0.45}, 0.0));
	auto& ls = f.labeled;
	ls.labels = cv::Mat(1, n, CV_8U, cv::Scalar(0));
	ls.validMask = cv::Mat(1, n, CV_8U, cv::Scalar(1));
	ls.points = cv::Mat(1, n, CV_32FC3);
	ls.regionIds = cv::Mat(1, n, CV_32S, cv::Scalar(-1));
	ls.roughnessBar = cv::Mat(1, n, CV_32F, cv::Scalar(1.0f));
	for (int i = 0; i < n; i++)
	{
		ls.points.at<cv::Vec3f>(0, i) = cv::Vec3f(
		    static_cast<float>(pts[i].x), static_cast<float>(pts[i].y),
		    static_cast<float>(pts[i].z));
		ls.labels.at<uint8_t>(0, i) = static_cast<uint8_t>(pts[i].label);
	}
	return f;
}

/** Floor points on a fan in front of the robot, out to `range`. */
inline std::vector<FakePoint> floorFan(double range, double step = 0.04)
{
	std::vector<FakePoint> pts;
	for (double a = -0.6; a <= 0.6; a += 0.02)
		for (double r = 0.3; r <= range; r += step)
			pts.push_back(
			    {r * std::cos(a), r * std::sin(a), 0.0, Label::Floor});
	return pts;
}

}  // namespace semnav::test
