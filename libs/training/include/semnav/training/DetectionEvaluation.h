/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/detection/CascadeDetector.h>
#include <semnav/perception/LabeledSweep.h>
#include <semnav/perception/PerceptionPipeline.h>
#include <semnav/training/GroundTruthObject.h>
#include <semnav/training/ObjectScorer.h>
#include <semnav/training/SimDataset.h>

#include <map>
#include <string>
#include <vector>

namespace semnav
{
/** semnav-detect's evaluation: perception and the cascade detector on
 * simulated sweeps, scored against their ground truth by issue 4's rule (a
 * ground-truth object counts from kCountedPixels visible pixels; a
 * detection matches it from IoU kMatchIou), and by two figures beside it
 * (objects the sensor cannot resolve left out), with how far the counted
 * objects get through the detector (Funnel) and why candidates were
 * rejected. */
class DetectionEvaluation
{
public:
	static constexpr int kCountedPixels = 150;
	static constexpr double kMatchIou = 0.3;
	/** Cell side for counting an object's distinct points (m). */
	static constexpr double kCellM = 0.02;

	/** How far the counted objects of a class get: a candidate of their
	 * label reaches them (measured box IoU >= kMatchIou), one of those
	 * passes the size check (then accepted, or rejected by the shape check
	 * or as a duplicate), one is accepted. */
	struct Funnel
	{
		std::size_t counted = 0, reached = 0, sized = 0, accepted = 0;
	};

	/** A figure beside issue 4's: the same detections, some counted
	 * objects left out (as too small to count). */
	struct OtherCount
	{
		explicit OtherCount(std::string t) : title(std::move(t)) {}
		std::string title;
		ObjectScorer scorer{kCountedPixels, kMatchIou};
		std::map<Label, std::size_t> excluded;
		/** Scores `labels` without the objects in `left` (keys of other
		 * labels are not counted). */
		void add(
		    const std::vector<Detection>& dets, const cv::Mat& groundTruth,
		    const std::vector<Label>& labels,
		    const ObjectScorer::ObjectKeys& left);
	};

	/** What one sweep gave (for diagnostics). */
	struct SweepResult
	{
		LabeledSweep perception;
		std::vector<CascadeDetector::Candidate> candidates;
		/** The ground-truth objects of the detector's classes. */
		std::vector<GroundTruthObject> objects;
	};

	/** Throws ConfigError/CascadeError naming a model that cannot be
	 * loaded. */
	explicit DetectionEvaluation(const CascadeDetector::TOptions& options);

	/** Detects in one sweep and scores it. */
	SweepResult add(const SimSweep& sweep);

	/** The classes with a cascade. */
	const std::vector<Label>& labels() const { return m_labels; }
	const CascadeDetector::TOptions& options() const { return m_options; }
	CascadeDetector& detector() { return m_detector; }
	/** Issue 4's scores. */
	const ObjectScorer& scorer() const { return m_scorer; }
	/** Without views beside the robot or seen over less than half their
	 * height. */
	const OtherCount& recognisable() const { return m_recognisable; }
	/** Per ground-truth instance id of the detector's classes and of
	 * doors (the map's objects): the sweeps where it was a recognisable
	 * view (counted and not left out by ObjectScorer::unrecognisable).
	 * Ids are per scene: over several datasets the counts of equal ids add
	 * up. */
	const std::map<int, std::size_t>& recognisableViews() const
	{
		return m_recognisableViews;
	}
	/** Objects counted by their distinct points, not pixels. */
	const OtherCount& distinct() const { return m_distinct; }
	const std::map<Label, Funnel>& funnels() const { return m_funnels; }
	/** "<label>: <reason>" -> rejected candidates. */
	const std::map<std::string, std::size_t>& rejections() const
	{
		return m_rejections;
	}
	/** Detection time per sweep, and of its cascades, ms. */
	const std::vector<double>& msTotal() const { return m_ms; }
	const std::vector<double>& msCascades() const { return m_msCascades; }

private:
	void addToFunnels(const SweepResult& r);

	CascadeDetector::TOptions m_options;
	CascadeDetector m_detector;
	std::vector<Label> m_labels;
	/** m_labels and doors: the labels of recognisableViews(). */
	std::vector<Label> m_viewLabels;
	PerceptionPipeline m_pipeline;
	ObjectScorer m_scorer{kCountedPixels, kMatchIou};
	OtherCount m_recognisable, m_distinct;
	std::map<int, std::size_t> m_recognisableViews;
	std::map<std::string, std::size_t> m_rejections;
	std::map<Label, Funnel> m_funnels;
	std::vector<double> m_ms, m_msCascades;
};

}  // namespace semnav
