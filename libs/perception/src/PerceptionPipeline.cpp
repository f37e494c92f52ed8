/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/Timing.h>
#include <semnav/perception/PerceptionPipeline.h>

#include <chrono>

namespace semnav
{
namespace
{
/** A sensor this high above its sweep's frame origin (m) is mounted on a
 * robot whose frame stands on the floor. */
constexpr double kMinMountingHeight = 0.05;
}  // namespace

const std::vector<std::string>& PerceptionPipeline::sections()
{
	static const std::vector<std::string> s = {
	    "NormalImage", "RangeSegmentation", "Roughness", "RuleClassifier"};
	return s;
}

void PerceptionPipeline::TOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& c, const std::string& prefix)
{
	normals.loadFromConfigFile(c, prefix + "NormalImage");
	segmentation.loadFromConfigFile(c, prefix + "RangeSegmentation");
	roughness.loadFromConfigFile(c, prefix + "Roughness");
	classifier.loadFromConfigFile(c, prefix + "RuleClassifier");
}

void PerceptionPipeline::TOptions::saveToConfigFile(
    mrpt::config::CConfigFileBase& c, const std::string& prefix) const
{
	normals.saveToConfigFile(c, prefix + "NormalImage");
	segmentation.saveToConfigFile(c, prefix + "RangeSegmentation");
	roughness.saveToConfigFile(c, prefix + "Roughness");
	classifier.saveToConfigFile(c, prefix + "RuleClassifier");
}

PerceptionPipeline::PerceptionPipeline() : PerceptionPipeline(TOptions()) {}

PerceptionPipeline::PerceptionPipeline(const TOptions& options)
    : mrpt::system::COutputLogger("PerceptionPipeline"),
      m_options(options),
      m_normals(options.normals),
      m_segmentation(options.segmentation),
      m_roughness(options.roughness),
      m_classifier(options.classifier)
{
}

LabeledSweep PerceptionPipeline::process(const Sweep& sweep)
{
	LabeledSweep out;
	process(sweep, out);
	return out;
}

void PerceptionPipeline::process(const Sweep& sweep, LabeledSweep& out)
{
	using clock = std::chrono::steady_clock;
	const auto t0 = clock::now();
	out.sweepIndex = sweep.index();
	out.detections.clear();

	auto t = clock::now();
	m_normals.compute(sweep);
	m_timings.normals = msSince(t);

	t = clock::now();
	m_segmentation.compute(sweep);
	m_timings.segmentation = msSince(t);

	t = clock::now();
	m_roughness.compute(m_normals, m_segmentation.areaIds());
	m_timings.roughness = msSince(t);

	t = clock::now();
	m_classifier.setMinLoggingLevel(getMinLoggingLevel());
	// A sensor mounted above the frame's origin: the robot's frame, on the
	// floor (3DTK scans are in the sensor's own frame).
	const bool floorReferenced =
	    !sweep.empty() && sweep.sensorPose(0).z() > kMinMountingHeight;
	m_classifier.classify(
	    m_normals, m_segmentation.areaIds(), m_roughness, out, floorReferenced);
	m_timings.classification = msSince(t);

	// The result owns its images (the stages reuse their buffers).
	// The results move into `out` by swapping buffers (no copy); the
	// stages get out's previous buffers to reuse next time.
	m_normals.swapOutputs(
	    out.points, out.validMask, out.normals, out.normalMask);
	m_segmentation.swapOutputs(out.areaIds);
	m_roughness.swapOutputs(out.roughness, out.roughnessBar);
	m_timings.total = msSince(t0);

	if (sweep.empty())
		MRPT_LOG_WARN_FMT("sweep %zu is empty", sweep.index());
	else if (m_normals.validPoints() == 0)
		MRPT_LOG_WARN_FMT("sweep %zu has no valid range", sweep.index());
}

}  // namespace semnav
