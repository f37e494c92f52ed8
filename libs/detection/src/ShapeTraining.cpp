/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/detection/GroundTruthObject.h>
#include <semnav/detection/ObjectScorer.h>
#include <semnav/detection/ShapeTraining.h>
#include <semnav/detection/SimDataset.h>
#include <semnav/perception/PerceptionPipeline.h>

#include <algorithm>
#include <opencv2/core.hpp>

namespace semnav
{
ShapeTraining::Samples ShapeTraining::collect(
    const std::vector<std::string>& datasets,
    CascadeDetector::TOptions detector, Label label, const Params& params,
    const std::function<void(const std::string&, std::size_t, std::size_t)>&
        progress)
{
	// Only this class, without a shape check, looser if asked.
	const CascadeDetector::TClassOptions k = detector.classOptions(label);
	detector.classes = {k};
	detector.classes[0].shapeModel.clear();
	if (params.minNeighbors >= 0)
		detector.classes[0].minNeighbors = params.minNeighbors;
	if (params.maxStages >= 0) detector.classes[0].maxStages = params.maxStages;
	CascadeDetector cascades(detector);
	cascades.describeShapes(true);
	PerceptionPipeline pipeline;
	Samples out;
	std::vector<float> rows;
	std::vector<int> isObject;
	for (const auto& dir : datasets)
	{
		const auto sweeps = SimDataset::load(dir);
		for (std::size_t i = 0; i < sweeps.size(); i++)
		{
			const auto& sw = sweeps[i].sweep;
			const LabeledSweep ls = pipeline.process(sw);
			const auto objects = GroundTruthObject::fromLabelImage(
			    sweeps[i].groundTruth, {label});
			for (const auto& c : cascades.detectCandidates(
			         sw.phis(), sw.thetas(), ls.normals, ls.normalMask,
			         ls.points, ls.groundZ, ls.labels, ls.areaIds))
			{
				if (!c.shape) continue;
				double best = 0;
				for (const auto& g : objects)
					best = std::max(
					    best, ObjectScorer::iou(c.measure->box, g.box));
				if (best >= params.objectIou)
					out.objects++;
				else if (best < params.otherIou)
					out.others++;
				else
				{
					out.ambiguous++;
					continue;
				}
				rows.insert(rows.end(), c.shape->begin(), c.shape->end());
				isObject.push_back(best >= params.objectIou ? 1 : 0);
			}
			out.sweeps++;
			if (progress) progress(dir, i + 1, sweeps.size());
		}
	}
	if (params.maxObjectsPerOther > 0 &&
	    double(out.objects) > params.maxObjectsPerOther * double(out.others))
	{
		// A seeded random subset of the objects.
		std::vector<std::size_t> objects;
		for (std::size_t i = 0; i < isObject.size(); i++)
			if (isObject[i]) objects.push_back(i);
		cv::RNG rng(params.seed);
		for (std::size_t i = objects.size(); i > 1; i--)
			std::swap(objects[i - 1], objects[rng.uniform(0, int(i))]);
		const auto keep = static_cast<std::size_t>(
		    params.maxObjectsPerOther * double(out.others));
		std::vector<bool> drop(isObject.size(), false);
		for (std::size_t i = keep; i < objects.size(); i++)
			drop[objects[i]] = true;
		std::vector<float> keptRows;
		std::vector<int> kept;
		for (std::size_t i = 0; i < isObject.size(); i++)
		{
			if (drop[i]) continue;
			keptRows.insert(
			    keptRows.end(), rows.begin() + long(i * ObjectShape::kFeatures),
			    rows.begin() + long((i + 1) * ObjectShape::kFeatures));
			kept.push_back(isObject[i]);
		}
		rows.swap(keptRows);
		isObject.swap(kept);
		out.objects = keep;
	}
	const int n = static_cast<int>(isObject.size());
	out.features =
	    cv::Mat(n, ObjectShape::kFeatures, CV_32F, rows.data()).clone();
	out.isObject = cv::Mat(n, 1, CV_32S, isObject.data()).clone();
	return out;
}

}  // namespace semnav
