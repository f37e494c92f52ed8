/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/detection/CascadeDetector.h>
#include <semnav/perception/LabeledSweep.h>
#include <semnav/perception/PerceptionPipeline.h>
#include <semnav/scan/Sweep.h>

#include <memory>
#include <optional>
#include <vector>

namespace semnav
{
/** Everything docs/design.md's data flow does to one sweep before the map: the
 * rule-based PerceptionPipeline (normals, segmentation, roughness, rules)
 * and, when cascades are configured, the CascadeDetector (washbasin,
 * wastebasket, stairs with the 3D size check). Used by semnav-perceive and
 * semnav-map alike. */
class SweepPerception
{
public:
	/** Wall-clock times of the last process(), ms. */
	struct Timings
	{
		double rules = 0, detection = 0, total = 0;
	};

	/** Without `cascades` no objects are detected. Throws ConfigError or
	 * CascadeError when a cascade cannot be loaded. */
	SweepPerception(
	    const PerceptionPipeline::TOptions& rules,
	    const std::optional<CascadeDetector::TOptions>& cascades);
	~SweepPerception();

	void process(const Sweep& sweep, LabeledSweep& out);
	LabeledSweep process(const Sweep& sweep);

	bool detectsObjects() const { return m_detector != nullptr; }
	/** The labels with a cascade (empty without cascades). */
	std::vector<Label> objectLabels() const;
	const Timings& lastTimings() const { return m_timings; }
	PerceptionPipeline& pipeline() { return m_pipeline; }

private:
	PerceptionPipeline m_pipeline;
	std::unique_ptr<CascadeDetector> m_detector;
	Timings m_timings;
};

}  // namespace semnav
