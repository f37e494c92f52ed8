/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once
#include <mrpt/math/TPoint3D.h>
#include <semnav/scan/Sweep.h>

namespace semnav
{
/** What a sweep had in view: whether an object at a point of the robot's
 * frame was within the sweep's field of view and bearing, large enough in
 * pixels for the detectors, and not hidden (the sweep's range toward it
 * reaches it, or finds nothing).
 *
 * The map counts an instance's views with it (ObjectInstance::views); the
 * localizer asks it where a map object would be at a candidate pose (an
 * object the map predicts in view but the detectors missed counts against
 * that pose). Holds a reference to the sweep, which must outlive it. */
class SweepView
{
public:
	/** `maxBearing` (rad): views only within it of the robot's heading;
	 * `minPixels`: the object must cover this many of the sweep's pixels. */
	SweepView(const Sweep& sweep, double maxBearing, double minPixels);
	/** `centroid`: the object's centre in the robot frame; `size`: its
	 * width across the line of sight (x) and height (z), m. */
	bool sees(
	    const mrpt::math::TPoint3D& centroid,
	    const mrpt::math::TPoint3D& size) const;
	/** Share of a 3 x 3 grid of points over the object's face (across the
	 * line of sight: its width x, height z; at the middle and +-1/3 of
	 * each) that the sweep sees: inside its field of view and not hidden.
	 * 0 when the centroid is out of range or beyond the bearing, or the
	 * object would cover fewer than `minPixels` pixels. A door half behind
	 * a wall corner or a cupboard scores 1/3-2/3, one in the open 1. */
	double visibleShare(
	    const mrpt::math::TPoint3D& centroid,
	    const mrpt::math::TPoint3D& size) const;

private:
	/** Whether the point (robot frame) at distance `d` from the tilt axis
	 * is inside the field of view and not hidden (the range at its pixel,
	 * or a neighbour's, reaches it or finds nothing). */
	bool unhidden(const mrpt::math::TPoint3D& p) const;
	/** The checks of sees() but the occlusion: range, field of view,
	 * bearing and pixels. */
	bool inField(
	    const mrpt::math::TPoint3D& centroid,
	    const mrpt::math::TPoint3D& size) const;

	const Sweep& m_sweep;
	double m_maxBearing, m_minPixels;
	double m_phiStep = 1, m_thetaStep = 1;
};

}  // namespace semnav
