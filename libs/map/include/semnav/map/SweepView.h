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

private:
	const Sweep& m_sweep;
	double m_maxBearing, m_minPixels;
	double m_phiStep = 1, m_thetaStep = 1;
};

}  // namespace semnav
