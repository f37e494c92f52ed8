/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/Percentile.h>
#include <semnav/nav/NavigationErrors.h>
#include <semnav/nav/NavigationLoop.h>
#include <semnav/robot/ControlClock.h>
#include <semnav/robot/RobotBase.h>

namespace semnav
{
NavigationLoop::NavigationLoop(
    SemanticNavigator& navigator, const RobotInterfaces& robot,
    StopAndScanLocalizer* localizer)
    : m_nav(navigator), m_robot(robot), m_localizer(localizer)
{
}

NavigationLoop::Result NavigationLoop::run(
    double deadline, const StepHook& hook)
{
	Result r;
	m_stepMs.clear();
	m_failureRescans = 0;
	for (int attempt = 0;; attempt++)
	{
		drive(deadline, hook, r);
		if (m_nav.state() == SemanticNavigator::State::Failed)
		{
			if (recoverFromFailure(r)) continue;
			break;
		}
		if (m_nav.state() != SemanticNavigator::State::Reached ||
		    !m_localizer || !m_localizer->options().arrivalCheck)
			break;
		auto check = m_localizer->confirmArrival(
		    m_robot, m_nav.command(), m_nav.goalObjectId());
		r.rescans.insert(
		    r.rescans.end(), check.records.begin(), check.records.end());
		if (check.relocalized) r.recoveries++;
		r.arrivals.push_back(check);
		if (check.confirmed) break;
		if (attempt >= m_localizer->options().arrivalAttempts)
		{
			m_nav.refuseArrival("arrival not confirmed: " + check.reason);
			break;
		}
		if (!check.relocalized && !relocalize(r, check.reason)) break;
		m_nav.notifyPoseCorrected();
		if (!m_nav.retry()) break;
	}
	if (!m_stepMs.empty()) r.medianStepMs = median(m_stepMs);
	return r;
}

bool NavigationLoop::recoverFromFailure(Result& r)
{
	// No path (or the start or the goal blocked, or no progress) may come
	// from a wrong belief: a carried robot plans from where it is not. One
	// stop-and-scan: when it finds the robot lost it relocalizes it, and the
	// navigator tries again from the corrected pose.
	using R = SemanticNavigator::StopReason;
	const R why = m_nav.stopReason();
	if (!m_localizer || m_localizer->options().rescanDistance <= 0 ||
	    m_failureRescans >= m_localizer->options().arrivalAttempts ||
	    (why != R::NoPath && why != R::StartBlocked && why != R::GoalBlocked &&
	     why != R::NoProgress))
		return false;
	m_failureRescans++;
	const auto rep = m_localizer->rescan(m_robot);
	r.rescans.insert(r.rescans.end(), rep.records.begin(), rep.records.end());
	if (!rep.recovery) return false;
	r.recoveries++;
	return m_nav.retry(SemanticNavigator::ReplanReason::Relocalized);
}

bool NavigationLoop::relocalize(Result& r, const std::string& why)
{
	// The goal is not where the robot believes it is: the belief is wrong.
	// Localize again from scratch where it stands (global, with the
	// uniqueness check) before trying again.
	try
	{
		const auto rep =
		    m_localizer->start(m_robot, StopAndScanLocalizer::Mode::Global);
		r.rescans.insert(
		    r.rescans.end(), rep.records.begin(), rep.records.end());
		r.recoveries++;
		return true;
	}
	catch (const LocalizationFailedError& e)
	{
		m_nav.refuseArrival(
		    "arrival not confirmed (" + why + ") and " + e.what());
		return false;
	}
}

void NavigationLoop::drive(double deadline, const StepHook& hook, Result& r)
{
	const double rescanDistance =
	    m_localizer ? m_localizer->options().rescanDistance : 0.0;
	double lastScanAt = m_robot.base->odometry().distance;
	while (m_nav.state() == SemanticNavigator::State::Navigating)
	{
		if (m_robot.clock->now() >= deadline)
		{
			m_nav.cancel(SemanticNavigator::StopReason::Timeout);
			break;
		}
		m_nav.step();
		m_stepMs.push_back(m_nav.lastStepMs());
		r.steps++;
		if (m_nav.state() != SemanticNavigator::State::Navigating) break;
		m_robot.clock->tick();
		const double travelled = m_robot.base->odometry().distance;
		if (rescanDistance > 0 && travelled - lastScanAt >= rescanDistance)
		{
			const auto rep = m_localizer->rescan(m_robot);
			r.rescans.insert(
			    r.rescans.end(), rep.records.begin(), rep.records.end());
			if (rep.recovery) r.recoveries++;
			m_nav.notifyPoseCorrected();
			lastScanAt = m_robot.base->odometry().distance;
		}
		if (hook) hook(m_robot.clock->now(), m_nav);
	}
}

}  // namespace semnav
