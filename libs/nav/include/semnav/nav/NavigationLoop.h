/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/nav/SemanticNavigator.h>
#include <semnav/nav/StopAndScanLocalizer.h>
#include <semnav/robot/RobotInterfaces.h>

#include <functional>
#include <vector>

namespace semnav
{
/** The control loop of one started command, the same on a robot and in the
 * simulator: a SemanticNavigator step every control period of the robot's
 * clock until the navigator stops or the deadline passes; with a localizer
 * whose rescan_distance_m > 0, every that much odometry travel the robot
 * stops and scans (StopAndScanLocalizer::rescan) and the navigator forgets
 * the obstacles placed with the old estimate. With the localizer's
 * arrival_check, an arrival is confirmed by a sweep at the goal
 * (StopAndScanLocalizer::confirmArrival); an unconfirmed one navigates
 * again after a global relocalization where it stands (arrival_attempts)
 * and then fails with
 * StopReason::ArrivalNotConfirmed. With rescans on, a navigator that stops
 * without a path first gets one stop-and-scan: a robot found lost (carried
 * away) is relocalized and navigates on. */
class NavigationLoop
{
public:
	struct Result
	{
		int steps = 0;
		/** Median wall time of one navigator step, ms. */
		double medianStepMs = 0;
		/** The stop-and-scan updates on the way. */
		std::vector<StopAndScanLocalizer::SweepRecord> rescans;
		/** Rescans that found the robot lost and relocalized it. */
		int recoveries = 0;
		/** The arrival checks at the goal (one per believed arrival). */
		std::vector<StopAndScanLocalizer::ArrivalCheck> arrivals;
	};

	/** Called after every period with the clock's time; may change the map
	 * and call notifyMapChanged(). */
	using StepHook = std::function<void(double time, SemanticNavigator&)>;

	/** `localizer` may be nullptr (no rescans). All must outlive run(). */
	NavigationLoop(
	    SemanticNavigator& navigator, const RobotInterfaces& robot,
	    StopAndScanLocalizer* localizer);

	/** Runs until the navigator stops; at clock time `deadline` it is
	 * cancelled with StopReason::Timeout. Throws LocalizationFailedError
	 * from a rescan. */
	Result run(double deadline, const StepHook& hook = {});

private:
	/** After the navigator failed (no path, start or goal blocked, no
	 * progress): one stop-and-scan; true when it found the robot lost,
	 * relocalized it and the navigator is under way again. */
	bool recoverFromFailure(Result& r);
	/** A global start where the robot stands after an unconfirmed arrival;
	 * false (navigator failed with the reason) when it does not converge. */
	bool relocalize(Result& r, const std::string& why);
	/** Steps until the navigator stops (or the deadline). */
	void drive(double deadline, const StepHook& hook, Result& r);

	std::vector<double> m_stepMs;
	int m_failureRescans = 0;
	SemanticNavigator& m_nav;
	RobotInterfaces m_robot;
	StopAndScanLocalizer* m_localizer;
};

}  // namespace semnav
