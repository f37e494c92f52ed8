/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/Percentile.h>
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
	const double rescanDistance =
	    m_localizer ? m_localizer->options().rescanDistance : 0.0;
	double lastScanAt = m_robot.base->odometry().distance;
	std::vector<double> stepMs;
	while (m_nav.state() == SemanticNavigator::State::Navigating)
	{
		if (m_robot.clock->now() >= deadline)
		{
			m_nav.cancel(SemanticNavigator::StopReason::Timeout);
			break;
		}
		m_nav.step();
		stepMs.push_back(m_nav.lastStepMs());
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
	if (!stepMs.empty()) r.medianStepMs = median(stepMs);
	return r;
}

}  // namespace semnav
