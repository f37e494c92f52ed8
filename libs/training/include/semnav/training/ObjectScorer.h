/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/common/Label.h>
#include <semnav/perception/Detection.h>

#include <array>
#include <opencv2/core/mat.hpp>
#include <set>
#include <utility>
#include <vector>

namespace semnav
{
/** Object-level precision and recall of detections against ground truth,
 * accumulated over sweeps (issue 4's rule): a ground-truth object counts
 * in a sweep when at least `minPixels` (150) of its pixels are visible; a
 * detection is a true positive when its box has IoU >= `minIou` (0.3) with
 * a not yet matched counted object of its label (detections taken by
 * decreasing score), otherwise a false positive, except that a detection
 * of an object too small to count (IoU >= minIou with an uncounted object
 * of its label) is ignored rather than called false: it found something
 * real that the rule does not ask for. Counted objects left unmatched are
 * false negatives. */
class ObjectScorer
{
public:
	struct Score
	{
		std::size_t tp = 0, fp = 0, fn = 0;
		/** Detections of too-small objects (neither tp nor fp). */
		std::size_t ignored = 0;
		/** 0 when undefined. */
		double precision = 0, recall = 0;
	};

	explicit ObjectScorer(int minPixels = 150, double minIou = 0.3);

	/** Ground-truth objects of one sweep, as (label, instance). */
	using ObjectKeys = std::set<std::pair<Label, int>>;

	/** Adds one sweep: its detections and its CV_16U ground-truth image
	 * (low byte label, high byte instance). Only labels in `labels` are
	 * scored. Objects in `excluded` are treated as too small to count
	 * (not scored; a detection of one is ignored), e.g. views no window
	 * detector can recognise, for a second figure beside the issue's. */
	void add(
	    const std::vector<Detection>& detections, const cv::Mat& groundTruth,
	    const std::vector<Label>& labels, const ObjectKeys& excluded = {});

	/** The counted objects of a sweep no window detector can be expected
	 * to recognise (for `excluded`): beside the robot (the mean of their
	 * points at a bearing of at least 80 deg, where the tilting scanner
	 * sees a thin slice), or visible over less than half of their height
	 * (top above `groundZ`: objects stand on the floor), e.g. cut by the
	 * lowest tilt line. `points`: the sweep's CV_32FC3 points. */
	ObjectKeys unrecognisable(
	    const cv::Mat& groundTruth, const cv::Mat& points, double groundZ,
	    const std::vector<Label>& labels) const;

	/** The counted objects of a sweep (for `excluded`) whose points fill
	 * fewer than minPixels cells of side `cellM` (m): beside the robot the
	 * tilt axis points at an object, and its pixels repeat a few points. */
	ObjectKeys fewDistinctPoints(
	    const cv::Mat& groundTruth, const cv::Mat& points,
	    const std::vector<Label>& labels, double cellM = 0.02) const;

	/** Cells of side `cellM` (m) that the valid points of the CV_8U
	 * `mask`'s pixels occupy. */
	static std::size_t distinctCells(
	    const cv::Mat& mask, const cv::Mat& points, double cellM);

	Score score(Label l) const;
	std::size_t sweeps() const { return m_sweeps; }

	static double iou(const cv::Rect& a, const cv::Rect& b);

private:
	int m_minPixels;
	double m_minIou;
	std::array<Score, kMaxLabelCount> m_scores{};
	std::size_t m_sweeps = 0;
};

}  // namespace semnav
