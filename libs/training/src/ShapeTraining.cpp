/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/perception/PerceptionPipeline.h>
#include <semnav/training/GroundTruthObject.h>
#include <semnav/training/ObjectScorer.h>
#include <semnav/training/ShapeTraining.h>
#include <semnav/training/SimDataset.h>

#include <algorithm>
#include <opencv2/core.hpp>

namespace semnav
{
namespace
{
/** The detector for `label` alone, as the shape forest learns it: without
 * a shape check, the taller check, merging and growing; looser if
 * `params` ask. */
CascadeDetector::TOptions shapeDetector(
    CascadeDetector::TOptions detector, Label label,
    const ShapeTraining::Params& params)
{
	// Only this class, without a shape check, looser if asked.
	const CascadeDetector::TClassOptions k = detector.classOptions(label);
	detector.classes = {k};
	detector.classes[0].shapeModel.clear();
	// The forest learns every candidate the size check passes; the taller
	// check is a rule of its own at detection.
	detector.classes[0].maxContinuingShare = 1;
	// Each candidate is learnt by its own box: merging the parts of one
	// object (min_separation_m) and growing it (grow_m) come after the
	// forest.
	detector.classes[0].minSeparation = 0;
	detector.classes[0].grow = 0;
	if (params.minNeighbors >= 0)
		detector.classes[0].minNeighbors = params.minNeighbors;
	if (params.maxStages >= 0) detector.classes[0].maxStages = params.maxStages;
	return detector;
}

/** Whether candidate `c` is an object (1), another thing (0) or ambiguous
 * (-1, counted in `out`): its best overlap with a ground-truth object of
 * the class, and that object's share of its pixels. */
int candidateKind(
    const CascadeDetector::Candidate& c,
    const std::vector<GroundTruthObject>& objects, const cv::Mat& groundTruth,
    const ShapeTraining::Params& params, ShapeTraining::Samples& out)
{
	double best = 0;
	const GroundTruthObject* bestObject = nullptr;
	for (const auto& g : objects)
	{
		const double v = ObjectScorer::iou(c.measure->box, g.box);
		if (v > best)
		{
			best = v;
			bestObject = &g;
		}
	}
	const bool object = best >= params.objectIou;
	if (!object && best >= params.otherIou)
	{
		out.ambiguous++;
		return -1;
	}
	if (object && params.minPurity > 0 &&
	    bestObject->shareOf(groundTruth, c.measure->pixels) < params.minPurity)
	{
		out.ambiguous++;
		out.impure++;
		return -1;
	}
	return object ? 1 : 0;
}

/** Seeded random subsets of the samples (`rows` of `columns` features,
 * `isObject`): objects to at most max_objects_per_other per other, then
 * both kinds in proportion to at most max_samples. */
void subsample(
    const ShapeTraining::Params& params, int columns, std::vector<float>& rows,
    std::vector<int>& isObject, ShapeTraining::Samples& out)
{
	// Seeded random subsets: objects to at most maxObjectsPerOther per other,
	// then both kinds in proportion to at most maxSamples.
	double keepObjects = double(out.objects), keepOthers = double(out.others);
	if (params.maxObjectsPerOther > 0)
		keepObjects =
		    std::min(keepObjects, params.maxObjectsPerOther * keepOthers);
	if (params.maxSamples > 0 && keepObjects + keepOthers > params.maxSamples)
	{
		const double f = double(params.maxSamples) / (keepObjects + keepOthers);
		keepObjects *= f;
		keepOthers *= f;
	}
	cv::RNG rng(params.seed);
	std::vector<bool> keep(isObject.size(), false);
	for (int kind : {1, 0})
	{
		std::vector<std::size_t> idx;
		for (std::size_t i = 0; i < isObject.size(); i++)
			if (isObject[i] == kind) idx.push_back(i);
		for (std::size_t i = idx.size(); i > 1; i--)
			std::swap(idx[i - 1], idx[std::size_t(rng.uniform(0, int(i)))]);
		const auto n = std::min(
		    idx.size(),
		    static_cast<std::size_t>(kind ? keepObjects : keepOthers));
		for (std::size_t i = 0; i < n; i++) keep[idx[i]] = true;
		(kind ? out.objects : out.others) = n;
	}
	std::vector<float> keptRows;
	std::vector<int> kept;
	for (std::size_t i = 0; i < isObject.size(); i++)
	{
		if (!keep[i]) continue;
		keptRows.insert(
		    keptRows.end(), rows.begin() + long(i) * columns,
		    rows.begin() + long(i + 1) * columns);
		kept.push_back(isObject[i]);
	}
	rows.swap(keptRows);
	isObject.swap(kept);
}
}  // namespace

ShapeTraining::Samples ShapeTraining::collect(
    const std::vector<std::string>& datasets,
    CascadeDetector::TOptions detector, Label label, const Params& params,
    const std::function<void(const std::string&, std::size_t, std::size_t)>&
        progress)
{
	CascadeDetector cascades(shapeDetector(detector, label, params));
	cascades.describeShapes(true);
	PerceptionPipeline pipeline;
	const std::vector<int> featureColumns = ObjectShape::columnsOf(
	    ObjectShape::featureCount(params.grids, params.steps));
	const int columns = int(featureColumns.size());
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
				const int kind = candidateKind(
				    c, objects, sweeps[i].groundTruth, params, out);
				if (kind < 0) continue;
				const bool object = kind == 1;
				(object ? out.objects : out.others)++;
				for (int k : featureColumns)
					rows.push_back((*c.shape)[std::size_t(k)]);
				isObject.push_back(object ? 1 : 0);
			}
			out.sweeps++;
			if (progress) progress(dir, i + 1, sweeps.size());
		}
	}
	subsample(params, columns, rows, isObject, out);
	const int n = static_cast<int>(isObject.size());
	out.features = cv::Mat(n, columns, CV_32F, rows.data()).clone();
	out.isObject = cv::Mat(n, 1, CV_32S, isObject.data()).clone();
	return out;
}

}  // namespace semnav
