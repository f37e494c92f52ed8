/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/detection/SweepPerception.h>

#include <chrono>

namespace semnav
{
SweepPerception::SweepPerception(
    const PerceptionPipeline::TOptions& rules,
    const std::optional<CascadeDetector::TOptions>& cascades)
    : m_pipeline(rules)
{
	if (cascades) m_detector = std::make_unique<CascadeDetector>(*cascades);
}

SweepPerception::~SweepPerception() = default;

void SweepPerception::process(const Sweep& sweep, LabeledSweep& out)
{
	const auto t0 = std::chrono::steady_clock::now();
	m_pipeline.process(sweep, out);
	const auto t1 = std::chrono::steady_clock::now();
	if (m_detector) m_detector->detect(sweep, out);
	const auto t2 = std::chrono::steady_clock::now();
	using ms = std::chrono::duration<double, std::milli>;
	m_timings.rules = ms(t1 - t0).count();
	m_timings.detection = ms(t2 - t1).count();
	m_timings.total = ms(t2 - t0).count();
}

LabeledSweep SweepPerception::process(const Sweep& sweep)
{
	LabeledSweep out;
	process(sweep, out);
	return out;
}

std::vector<Label> SweepPerception::objectLabels() const
{
	std::vector<Label> out;
	if (m_detector)
		for (const auto& c : m_detector->options().classes)
			out.push_back(c.label);
	return out;
}

}  // namespace semnav
