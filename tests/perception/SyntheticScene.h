/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

// A small ray caster for unit tests: axis-aligned boxes, a floor z = 0 with
// optional bumps and an optional ceiling, seen by the paper's tilting LMS200
// (theta -15..90 deg, phi -90..90 deg, 0.5 deg steps, tilt axis 0.45 m up)
// from the robot frame origin. Returns the Sweep and the true label of
// every pixel. Independent of libs/sim on purpose (perception's unit tests
// link semnav::perception only).

#include <semnav/common/Label.h>
#include <semnav/scan/Sweep.h>
#include <semnav/scan/TiltGeometry.h>

#include <cmath>
#include <functional>
#include <limits>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <random>
#include <vector>

namespace semnav::test
{
struct SynthBox
{
	cv::Vec3d lo, hi;
	Label label = Label::Obstacle;
};

struct SynthScene
{
	std::vector<SynthBox> boxes;
	/** Floor z = height(x, y) (default flat 0), label by position. */
	std::function<double(double, double)> height;
	std::function<Label(double, double)> groundLabel;
	/** Ceiling plane z = value, label Ceiling. */
	std::optional<double> ceiling;
	double maxRange = 8.0;
	/** Gaussian range noise std dev (m). */
	double noise = 0.0;
	unsigned seed = 1;
	/** Tilt axis position in the robot frame. */
	cv::Vec3d mount{0, 0, 0.45};
	double thetaMinDeg = -15, thetaMaxDeg = 90, stepDeg = 0.5;
};

/** Slab intersection of a ray with an axis-aligned box; t of entry. */
inline std::optional<double> hitBox(
    const cv::Vec3d& o, const cv::Vec3d& d, const SynthBox& b)
{
	double t0 = 0, t1 = std::numeric_limits<double>::max();
	for (int k = 0; k < 3; k++)
	{
		if (std::abs(d[k]) < 1e-12)
		{
			if (o[k] < b.lo[k] || o[k] > b.hi[k]) return std::nullopt;
			continue;
		}
		double a = (b.lo[k] - o[k]) / d[k], c = (b.hi[k] - o[k]) / d[k];
		if (a > c) std::swap(a, c);
		t0 = std::max(t0, a);
		t1 = std::min(t1, c);
		if (t0 > t1) return std::nullopt;
	}
	if (t0 <= 1e-9) return std::nullopt;  // inside: not seen
	return t0;
}

/** Renders the sweep; `labels` (CV_8U label ids, Unknown where no return)
 * if not null. */
inline Sweep renderSweep(const SynthScene& sc, cv::Mat* labels = nullptr)
{
	const double deg = M_PI / 180;
	const int rows = static_cast<int>(std::lround(
	                     (sc.thetaMaxDeg - sc.thetaMinDeg) / sc.stepDeg)) +
	                 1;
	const int cols = static_cast<int>(std::lround(180.0 / sc.stepDeg)) + 1;
	Sweep sw(rows, cols);
	std::vector<double> phi(cols);
	for (int c = 0; c < cols; c++) phi[c] = (-90.0 + c * sc.stepDeg) * deg;
	sw.setPhis(phi);
	sw.setMaxRange(static_cast<float>(sc.maxRange));
	if (labels) *labels = cv::Mat(rows, cols, CV_8U, cv::Scalar(0));
	std::mt19937 rng(sc.seed);
	std::normal_distribution<double> gauss(0.0, 1.0);
	for (int r = 0; r < rows; r++)
	{
		const double theta = (sc.thetaMinDeg + r * sc.stepDeg) * deg;
		const auto pose =
		    tiltedSensorPose({sc.mount[0], sc.mount[1], sc.mount[2]}, theta);
		sw.setRow(r, theta, pose);
		const auto& R = pose.getRotationMatrix();
		const cv::Vec3d o(pose.x(), pose.y(), pose.z());
		for (int c = 0; c < cols; c++)
		{
			const double lx = std::cos(phi[c]), ly = std::sin(phi[c]);
			const cv::Vec3d d(
			    R(0, 0) * lx + R(0, 1) * ly, R(1, 0) * lx + R(1, 1) * ly,
			    R(2, 0) * lx + R(2, 1) * ly);
			double best = std::numeric_limits<double>::max();
			Label lab = Label::Unknown;
			for (const auto& b : sc.boxes)
				if (auto t = hitBox(o, d, b); t && *t < best)
				{
					best = *t;
					lab = b.label;
				}
			if (d[2] < -1e-9)
			{
				// Floor: flat plane first, then Newton on the bumps.
				double t = -o[2] / d[2];
				if (sc.height)
					for (int it = 0; it < 8; it++)
					{
						const double eps = 1e-4;
						const cv::Vec3d p = o + t * d;
						const double f = p[2] - sc.height(p[0], p[1]);
						const cv::Vec3d q = o + (t + eps) * d;
						const double f2 = q[2] - sc.height(q[0], q[1]);
						const double df = (f2 - f) / eps;
						if (std::abs(df) < 1e-9) break;
						t -= f / df;
					}
				if (t > 0 && t < best)
				{
					best = t;
					const cv::Vec3d p = o + t * d;
					lab = sc.groundLabel ? sc.groundLabel(p[0], p[1])
					                     : Label::Floor;
				}
			}
			if (sc.ceiling && d[2] > 1e-9)
			{
				const double t = (*sc.ceiling - o[2]) / d[2];
				if (t > 0 && t < best)
				{
					best = t;
					lab = Label::Ceiling;
				}
			}
			if (best > sc.maxRange)
			{
				sw.setRange(r, c, static_cast<float>(sc.maxRange), false);
				continue;
			}
			const double meas = best + sc.noise * gauss(rng);
			sw.setRange(r, c, static_cast<float>(meas), meas > 0);
			if (labels) labels->at<uint8_t>(r, c) = static_cast<uint8_t>(lab);
		}
	}
	return sw;
}

/** A box room around the robot: floor, ceiling at `height`, walls 0.1 m
 * thick at x = xmin, xmax and y = ymin, ymax (inner faces). */
inline SynthScene boxRoom(
    double xmin, double xmax, double ymin, double ymax, double height)
{
	SynthScene sc;
	sc.ceiling = height;
	const double t = 0.1;
	sc.boxes.push_back(
	    {{xmin - t, ymin - t, 0}, {xmin, ymax + t, height}, Label::Wall});
	sc.boxes.push_back(
	    {{xmax, ymin - t, 0}, {xmax + t, ymax + t, height}, Label::Wall});
	sc.boxes.push_back(
	    {{xmin, ymin - t, 0}, {xmax, ymin, height}, Label::Wall});
	sc.boxes.push_back(
	    {{xmin, ymax, 0}, {xmax, ymax + t, height}, Label::Wall});
	return sc;
}

/** Pixel F1 of label l between a prediction and the true labels, over
 * pixels with a valid range. */
inline double pixelF1(
    const cv::Mat& pred, const cv::Mat& truth, const Sweep& sw, Label l)
{
	const auto v = static_cast<uint8_t>(l);
	double tp = 0, fp = 0, fn = 0;
	for (int r = 0; r < pred.rows; r++)
		for (int c = 0; c < pred.cols; c++)
		{
			if (!sw.valid(r, c)) continue;
			const bool p = pred.at<uint8_t>(r, c) == v,
			           t = truth.at<uint8_t>(r, c) == v;
			tp += p && t;
			fp += p && !t;
			fn += !p && t;
		}
	return tp == 0 ? 0.0 : 2 * tp / (2 * tp + fp + fn);
}

}  // namespace semnav::test
