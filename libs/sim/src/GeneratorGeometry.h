/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once
// Floor-plan geometry of SceneGenerator (src/ only): footprints as convex
// polygons, distances between points, segments and polygons.

#include <mrpt/math/TPoint2D.h>

#include <vector>

namespace semnav::detail
{
using Polygon2D = std::vector<mrpt::math::TPoint2D>;

/** Rectangle of full size sx x sy centred at (cx, cy), turned by yaw (rad). */
Polygon2D rectPolygon(double cx, double cy, double sx, double sy, double yaw);
/** Regular 12-gon around a circle (circumscribed). */
Polygon2D circlePolygon(double cx, double cy, double r);

double distPointSegment(
    const mrpt::math::TPoint2D& p, const mrpt::math::TPoint2D& a,
    const mrpt::math::TPoint2D& b);
/** Distance from p to a convex polygon (0 inside). */
double distPointPolygon(const mrpt::math::TPoint2D& p, const Polygon2D& poly);
/** Distance from segment ab to a convex polygon (0 when they meet). */
double distSegmentPolygon(
    const mrpt::math::TPoint2D& a, const mrpt::math::TPoint2D& b,
    const Polygon2D& poly);
/** Distance between two convex polygons (0 when they meet). */
double distPolygons(const Polygon2D& p, const Polygon2D& q);

}  // namespace semnav::detail
