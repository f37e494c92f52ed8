/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/training/DetectionEvaluation.h>

#include <algorithm>

namespace semnav
{
void DetectionEvaluation::OtherCount::add(
    const std::vector<Detection>& dets, const cv::Mat& groundTruth,
    const std::vector<Label>& labels, const ObjectScorer::ObjectKeys& left)
{
	for (const auto& k : left)
		if (std::find(labels.begin(), labels.end(), k.first) != labels.end())
			excluded[k.first]++;
	scorer.add(dets, groundTruth, labels, left);
}

DetectionEvaluation::DetectionEvaluation(
    const CascadeDetector::TOptions& options)
    : m_options(options),
      m_detector(options),
      // The same without the views no window detector can recognise (an
      // extra figure; issue 4's rule is m_scorer's)...
      m_recognisable(
          "without views beside the robot (|bearing| >= 80 deg) or seen over "
          "less than half their height"),
      // ...and objects counted by their distinct points, not pixels.
      m_distinct(
          "counted by distinct points (>= " + std::to_string(kCountedPixels) +
          " occupied 2 cm cells), not pixels")
{
	for (const auto& k : m_options.classes) m_labels.push_back(k.label);
	m_viewLabels = m_labels;
	if (std::find(m_labels.begin(), m_labels.end(), Label::Door) ==
	    m_labels.end())
		m_viewLabels.push_back(Label::Door);
}

DetectionEvaluation::SweepResult DetectionEvaluation::add(const SimSweep& s)
{
	SweepResult r;
	r.perception = m_pipeline.process(s.sweep);
	const auto& ls = r.perception;
	const auto& sw = s.sweep;
	r.candidates = m_detector.detectCandidates(
	    sw.phis(), sw.thetas(), ls.normals, ls.normalMask, ls.points,
	    ls.groundZ, ls.labels, ls.areaIds);
	m_ms.push_back(m_detector.lastTimings().total);
	m_msCascades.push_back(m_detector.lastTimings().cascades);
	std::vector<Detection> dets;
	for (const auto& c : r.candidates)
	{
		if (!c.accepted)
		{
			m_rejections[labelName(c.label) + ": " + c.rejection]++;
			continue;
		}
		Detection d;
		d.label = c.label;
		d.imageBox = c.measure->box;
		d.score = c.neighbours;
		dets.push_back(d);
	}
	m_scorer.add(dets, s.groundTruth, m_labels);
	r.objects = GroundTruthObject::fromLabelImage(s.groundTruth, m_labels);
	addToFunnels(r);
	// Doors too, for recognisableViews(); the scorer reads only m_labels.
	const auto unrecognisable = m_recognisable.scorer.unrecognisable(
	    s.groundTruth, ls.points, ls.groundZ, m_viewLabels);
	m_recognisable.add(dets, s.groundTruth, m_labels, unrecognisable);
	for (const auto& g :
	     GroundTruthObject::fromLabelImage(s.groundTruth, m_viewLabels))
		if (g.pixels >= kCountedPixels &&
		    !unrecognisable.count({g.label, g.instance}))
			m_recognisableViews[g.instance]++;
	m_distinct.add(
	    dets, s.groundTruth, m_labels,
	    m_distinct.scorer.fewDistinctPoints(
	        s.groundTruth, ls.points, m_labels, kCellM));
	return r;
}

void DetectionEvaluation::addToFunnels(const SweepResult& r)
{
	for (const auto& g : r.objects)
	{
		if (g.pixels < kCountedPixels) continue;
		bool reached = false, sized = false, accepted = false;
		for (const auto& c : r.candidates)
		{
			if (c.label != g.label || !c.measure ||
			    ObjectScorer::iou(c.measure->box, g.box) < kMatchIou)
				continue;
			reached = true;
			sized |= c.accepted || c.rejection == "shape" ||
			         c.rejection == "duplicate";
			accepted |= c.accepted;
		}
		Funnel& f = m_funnels[g.label];
		f.counted++;
		f.reached += reached;
		f.sized += sized;
		f.accepted += accepted;
	}
}
}  // namespace semnav
