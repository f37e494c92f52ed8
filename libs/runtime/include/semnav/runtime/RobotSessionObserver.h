/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/core/Clock.h>
#include <mrpt/math/TPose2D.h>
#include <semnav/nav/SemanticNavigator.h>

namespace semnav
{
class SemanticMap;
class Sweep;
class LabeledSweep;

/** What a RobotSession shows while it runs, for a viewer or a middleware
 * bridge (Ros1Operator). Every call comes on the session's control thread
 * and must return quickly: copy what is needed and do the work elsewhere.
 * The references are valid only during the call. */
class RobotSessionObserver
{
public:
	virtual ~RobotSessionObserver() = default;

	/** The map differs from the last one this observer accepted. Return
	 * false to be asked again at a later control period (e.g. throttled). */
	virtual bool onMapChanged(const SemanticMap& map) = 0;
	/** A new plan of the running command (map frame). */
	virtual void onPlan(const SemanticNavigator::PlanRecord& plan) = 0;
	/** Every control period (and ~10 Hz while idle): the believed map pose
	 * and the odometry reading (pose, stamp) it was composed from. */
	virtual void onPose(
	    const mrpt::math::TPose2D& pose, const mrpt::math::TPose2D& odometry,
	    mrpt::Clock::time_point odometryTime) = 0;
	/** A sweep the localizer took, perceived, with its map-frame estimate
	 * and that estimate's standard deviations (xy in m, yaw in rad). */
	virtual void onSweep(
	    const Sweep& sweep, const LabeledSweep& labeled,
	    const mrpt::math::TPose2D& estimate, double stdXY, double stdYaw) = 0;
};

}  // namespace semnav
