/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/math/TPoint2D.h>
#include <mrpt/poses/CPose2D.h>

#include <cmath>
#include <cstddef>
#include <vector>

namespace semnav
{
/** A wall seen from above: a 2D line segment fitted to the points of a
 * vertical planar area labelled wall, with its uncertainty. Robot frame for
 * an observation, world frame in a WallMap. */
struct WallSegment
{
	/** Endpoints (m). */
	mrpt::math::TPoint2D p0{0, 0}, p1{0, 0};
	/** Points the fit used. */
	std::size_t points = 0;
	/** Std dev of the points' distances to the line (m). */
	double residual = 0;
	/** Std dev of the line's direction (rad) and of its offset along the
	 * normal (m), from the fit. */
	double sigmaAngle = 0, sigmaOffset = 0;

	double length() const { return (p1 - p0).norm(); }
	/** Direction of p0 -> p1 (rad, (-pi, pi]). */
	double angle() const { return std::atan2(p1.y - p0.y, p1.x - p0.x); }
	/** pose (+) point in 2D. */
	static mrpt::math::TPoint2D compose(
	    const mrpt::poses::CPose2D& pose, const mrpt::math::TPoint2D& p)
	{
		return {
		    pose.x() + pose.phi_cos() * p.x - pose.phi_sin() * p.y,
		    pose.y() + pose.phi_sin() * p.x + pose.phi_cos() * p.y};
	}
	/** The segment seen from another frame: pose (+) segment. */
	WallSegment transformed(const mrpt::poses::CPose2D& pose) const
	{
		WallSegment s = *this;
		s.p0 = compose(pose, p0);
		s.p1 = compose(pose, p1);
		return s;
	}
};

/** Total-least-squares segment through the points (xs[i], ys[i]), at
 * least two: the principal axis of their scatter, its ends at the
 * endpointQuantile and 1 - endpointQuantile quantiles of the points along
 * it (0: the extreme points), its residual and sigmas from the fit. */
WallSegment fitWallSegment(
    const std::vector<double>& xs, const std::vector<double>& ys,
    double endpointQuantile);

}  // namespace semnav
