/* semnav: semantic navigation from tilting-laser sweeps */
// The shipped cascades (datasets/cascades/, scripts/train-cascades) on a
// held-out simulated scene: they load in cv::CascadeClassifier, semnav's
// evaluator agrees with OpenCV window by window on a real detection image,
// and the search's settings each do what they claim. The README's accuracy
// figures are held by detection_accuracy_test.cpp (twelve rooms).
#include <gtest/gtest.h>
#include <semnav/cascade/CascadeEvaluator.h>
#include <semnav/cascade/CascadeXml.h>
#include <semnav/detection/CascadeDetector.h>
#include <semnav/perception/PerceptionPipeline.h>
#include <semnav/sim/RayCaster.h>
#include <semnav/sim/SceneLoader.h>
#include <semnav/sim/SimulationRunner.h>
#include <semnav/sim/TiltingLaserSimulator.h>
#include <semnav/training/GroundTruthObject.h>
#include <semnav/training/ObjectScorer.h>
#include <semnav/training/ShapeTraining.h>

#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <opencv2/objdetect.hpp>
#include <set>
#include <tuple>

#include "../TestPaths.h"

using namespace semnav;

namespace
{

struct Simulated
{
	std::vector<Sweep> sweeps;
	std::vector<cv::Mat> groundTruth;
};

/** The held-out scene test_c, every sweep. */
const Simulated& scene()
{
	static const Simulated s = []
	{
		Simulated out;
		const Scene sc = SceneLoader::loadFile(
		    test::kSourceDir + "/datasets/cascade-scenes/test_c.yaml");
		RayCaster rc(sc, 1);
		TiltingLaserSimulator sim(rc, sc.sensor, 1);
		for (std::size_t k = 0; k < sc.trajectory.size(); k++)
		{
			const auto sw = sim.simulate(
			    sc.trajectory[k], k, SimulationRunner::epoch(), 1 / 37.5);
			out.sweeps.push_back(sw.toSweep());
			out.groundTruth.push_back(sw.labels);
		}
		return out;
	}();
	return s;
}

/** Every candidate of `d` on a perceived sweep. */
std::vector<CascadeDetector::Candidate> candidatesOf(
    CascadeDetector& d, const Sweep& sw, const LabeledSweep& ls)
{
	return d.detectCandidates(
	    sw.phis(), sw.thetas(), ls.normals, ls.normalMask, ls.points,
	    ls.groundZ, ls.labels, ls.areaIds);
}

/** A detector of `o` with `set` applied to each of its classes. */
template <typename Set>
std::unique_ptr<CascadeDetector> detectorWith(
    CascadeDetector::TOptions o, Set&& set)
{
	for (auto& k : o.classes) set(k);
	return std::make_unique<CascadeDetector>(o);
}

}  // namespace

/** The shipped detector options (config/cascade.ini); its cascades are
 * committed in datasets/cascades/. */
class CascadeDetection : public ::testing::Test
{
protected:
	void SetUp() override
	{
		opts = CascadeDetector::TOptions::fromIniFile(
		    test::kSourceDir + "/config/cascade.ini");
		for (const auto& k : opts.classes)
			ASSERT_TRUE(std::filesystem::exists(opts.cascadePath(k)))
			    << opts.cascadePath(k);
	}
	CascadeDetector::TOptions opts;
};

TEST_F(CascadeDetection, ShippedCascadesAgreeWithOpenCvOnASweep)
{
	const Simulated& s = scene();
	PerceptionPipeline p;
	const LabeledSweep ls = p.process(s.sweeps[3]);
	CascadeDetector det(opts);
	const cv::Mat img = det.detectionImage(
	    s.sweeps[3].phis(), s.sweeps[3].thetas(), ls.normals, ls.normalMask);
	for (const auto& k : opts.classes)
	{
		const HaarCascade c = CascadeXml::readFile(opts.cascadePath(k));
		EXPECT_TRUE(c.hasTiltedFeatures()) << labelName(k.label);
		EXPECT_GE(c.stages.size(), 10u) << labelName(k.label);
		cv::CascadeClassifier cc;
		ASSERT_TRUE(cc.load(opts.cascadePath(k)));
		// Windows passing the first stage, the first half, and all stages.
		for (std::size_t n :
		     {std::size_t(1), c.stages.size() / 2, c.stages.size()})
		{
			const HaarCascade part = c.firstStages(n);
			cv::CascadeClassifier partCv;
			const std::string xml = CascadeXml::toString(part);
			cv::FileStorage fs(
			    xml, cv::FileStorage::READ | cv::FileStorage::MEMORY);
			ASSERT_TRUE(partCv.read(fs.getFirstTopLevelNode()));
			std::vector<cv::Rect> found;
			partCv.detectMultiScale(
			    img, found, 1.1, 0, 0, c.windowSize, c.windowSize);
			std::map<std::pair<int, int>, int> cvSet;
			for (const auto& r : found) cvSet[{r.x, r.y}]++;
			CascadeEvaluator ev(part);
			ev.setImage(img);
			std::size_t mine = 0;
			for (const auto& w : ev.scanScaleOne())
				if (ev.accepted(w.result))
				{
					mine++;
					EXPECT_TRUE(cvSet.count({w.origin.x, w.origin.y}))
					    << labelName(k.label) << " " << n << " stages at "
					    << w.origin;
				}
			EXPECT_EQ(mine, found.size()) << labelName(k.label) << " " << n;
		}
	}
}

TEST_F(CascadeDetection, ProposalsKeepMostOfTheWholeImageDetections)
{
	const Simulated& s = scene();
	PerceptionPipeline p;
	opts.proposals = false;
	CascadeDetector whole(opts);
	opts.proposals = true;
	CascadeDetector proposed(opts);
	const std::vector<Label> labels{
	    Label::Washbasin, Label::Wastebasket, Label::Stairs};
	ObjectScorer scoreWhole, scoreProposed;
	for (std::size_t i = 0; i < s.sweeps.size(); i++)
	{
		const Sweep& sw = s.sweeps[i];
		LabeledSweep a = p.process(sw);
		LabeledSweep b = a;
		whole.detect(sw, a);
		proposed.detect(sw, b);
		scoreWhole.add(a.detections, s.groundTruth[i], labels);
		scoreProposed.add(b.detections, s.groundTruth[i], labels);
		// Every candidate of the proposal search lies in a search region
		// around a proposal of its class.
		const auto cands = candidatesOf(proposed, sw, b);
		ASSERT_EQ(proposed.lastProposals().size(), opts.classes.size());
		for (const auto& c : cands)
		{
			std::size_t k = 0;
			while (opts.classes[k].label != c.label) k++;
			bool inside = false;
			for (const auto& pr : proposed.lastProposals()[k])
				inside |= (c.box & pr.box).area() > 0;
			EXPECT_TRUE(inside) << labelName(c.label) << " " << c.box;
		}
	}
	std::size_t tpWhole = 0, tpProposed = 0;
	for (Label l : labels)
	{
		tpWhole += scoreWhole.score(l).tp;
		tpProposed += scoreProposed.score(l).tp;
		std::printf(
		    "%-12s whole image tp %zu fp %zu, proposals tp %zu fp %zu\n",
		    labelName(l).c_str(), scoreWhole.score(l).tp,
		    scoreWhole.score(l).fp, scoreProposed.score(l).tp,
		    scoreProposed.score(l).fp);
		// Measured: precision 0.95, 0.90, 1.00 (washbasin, wastebasket,
		// stairs); asserts >= 0.8.
		EXPECT_GE(scoreProposed.score(l).precision, 0.8) << labelName(l);
	}
	// Measured on this scene (this test's output): 45 true positives with
	// proposals, 45 on the whole image; asserts >= 90 % of the whole
	// image's.
	EXPECT_GE(double(tpProposed), 0.9 * double(tpWhole));
	EXPECT_GT(tpProposed, 0u);
}

TEST_F(CascadeDetection, RangeScalesWithTheGateOpenAreDetectMultiScale)
{
	// The range-gated search runs the pyramid, window steps and grouping of
	// detectMultiScale with the project's evaluator: with a gate that
	// admits every window with a range, it finds the same boxes. With every
	// stage: the gate skips windows without a range, so it does not skip
	// the window after one of them rejected at stage 0 as detectMultiScale
	// does; the full cascades reject what that lets in, the first stages
	// (max_stages) keep a few such windows, a box then moves by a pixel.
	const Simulated& s = scene();
	PerceptionPipeline p;
	for (auto& k : opts.classes)
	{
		k.maxStages = 0;
		k.windowStep = 0;  // detectMultiScale's steps
	}
	opts.proposals = false;
	opts.rangeScales = false;
	CascadeDetector opencv(opts);
	opts.rangeScales = true;
	opts.rangeScaleSlack = 10;
	opts.rangeCut = 100;
	opts.rangeObjectsOnly = false;
	CascadeDetector gated(opts);
	std::size_t boxes = 0;
	for (std::size_t i = 0; i < s.sweeps.size(); i += 4)
	{
		const Sweep& sw = s.sweeps[i];
		const LabeledSweep ls = p.process(sw);
		const auto run = [&](CascadeDetector& d)
		{
			std::vector<std::pair<Label, cv::Rect>> out;
			for (const auto& c : candidatesOf(d, sw, ls))
				out.emplace_back(c.label, c.box);
			std::sort(
			    out.begin(), out.end(),
			    [](const auto& x, const auto& y)
			    {
				    return std::make_tuple(
				               x.first, x.second.x, x.second.y, x.second.width,
				               x.second.height) <
				           std::make_tuple(
				               y.first, y.second.x, y.second.y, y.second.width,
				               y.second.height);
			    });
			return out;
		};
		const auto a = run(opencv), b = run(gated);
		EXPECT_EQ(a.size(), b.size()) << "sweep " << i;
		for (const auto& [x, y] : {std::pair{&a, &b}, std::pair{&b, &a}})
			for (const auto& w : *x)
				EXPECT_TRUE(std::find(y->begin(), y->end(), w) != y->end())
				    << "sweep " << i << ": " << labelName(w.first) << " "
				    << w.second << " only "
				    << (x == &a ? "in detectMultiScale" : "range-gated");
		boxes += a.size();
	}
	EXPECT_GT(boxes, 0u);
}

TEST_F(CascadeDetection, WindowStepTwoSearchesFewerWindows)
{
	// window_step 2 steps two level pixels at every level, where
	// detectMultiScale steps one above scale 2: without grouping, fewer
	// raw windows pass, but the search still finds candidates.
	const Simulated& s = scene();
	PerceptionPipeline p;
	opts.proposals = false;
	opts.rangeScales = true;
	for (auto& k : opts.classes) k.minNeighbors = 0;
	const auto candidates = [&](int step)
	{
		for (auto& k : opts.classes) k.windowStep = step;
		CascadeDetector d(opts);
		std::size_t n = 0;
		for (std::size_t i = 0; i < s.sweeps.size(); i += 6)
		{
			const Sweep& sw = s.sweeps[i];
			const LabeledSweep ls = p.process(sw);
			n += candidatesOf(d, sw, ls).size();
		}
		return n;
	};
	const std::size_t opencvSteps = candidates(0), two = candidates(2);
	std::printf(
	    "candidates: %zu with detectMultiScale's steps, %zu with 2\n",
	    opencvSteps, two);
	EXPECT_GT(two, 0u);
	EXPECT_LT(double(two), 0.8 * double(opencvSteps));
}

TEST_F(CascadeDetection, RangeScalesKeepTheWholeImageDetections)
{
	// Shipped gate (range_scales): windows only at the scales an object of
	// the class can have at their range, around object points.
	ASSERT_TRUE(opts.rangeScales);
	const Simulated& s = scene();
	PerceptionPipeline p;
	opts.proposals = false;
	CascadeDetector gated(opts);
	opts.rangeScales = false;
	CascadeDetector whole(opts);
	const std::vector<Label> labels{
	    Label::Washbasin, Label::Wastebasket, Label::Stairs};
	ObjectScorer scoreWhole, scoreGated;
	for (std::size_t i = 0; i < s.sweeps.size(); i++)
	{
		const Sweep& sw = s.sweeps[i];
		LabeledSweep a = p.process(sw);
		LabeledSweep b = a;
		whole.detect(sw, a);
		gated.detect(sw, b);
		scoreWhole.add(a.detections, s.groundTruth[i], labels);
		scoreGated.add(b.detections, s.groundTruth[i], labels);
	}
	for (Label l : labels)
	{
		std::printf(
		    "%-12s whole image tp %zu fp %zu, range scales tp %zu fp %zu\n",
		    labelName(l).c_str(), scoreWhole.score(l).tp,
		    scoreWhole.score(l).fp, scoreGated.score(l).tp,
		    scoreGated.score(l).fp);
		// Measured on this scene (this test's output): the same true
		// positives and false alarms per class; asserts a margin of one.
		EXPECT_GE(scoreGated.score(l).tp + 1, scoreWhole.score(l).tp)
		    << labelName(l);
		EXPECT_LE(scoreGated.score(l).fp, scoreWhole.score(l).fp + 1)
		    << labelName(l);
	}
}

TEST_F(CascadeDetection, ZeroBorderGivesWindowsAtTheImageEdge)
{
	const Simulated& s = scene();
	PerceptionPipeline p;
	const auto plainDetector =
	    detectorWith(opts, [](auto& k) { k.borderPx = 0; });
	const auto paddedDetector =
	    detectorWith(opts, [](auto& k) { k.borderPx = 24; });
	CascadeDetector &plain = *plainDetector, &padded = *paddedDetector;
	std::size_t atEdgePlain = 0, atEdgePadded = 0;
	for (std::size_t i = 0; i < s.sweeps.size(); i++)
	{
		const Sweep& sw = s.sweeps[i];
		const LabeledSweep ls = p.process(sw);
		const cv::Rect image(0, 0, int(sw.cols()), int(sw.rows()));
		const auto count = [&](CascadeDetector& d)
		{
			std::size_t n = 0;
			for (const auto& c : candidatesOf(d, sw, ls))
			{
				// Boxes come back clipped to the image.
				EXPECT_EQ(c.box & image, c.box);
				EXPECT_GT(c.box.area(), 0);
				n += c.box.x == 0 || c.box.y == 0 ||
				     c.box.x + c.box.width == image.width;
			}
			return n;
		};
		atEdgePlain += count(plain);
		atEdgePadded += count(padded);
	}
	// Windows reaching into the border are clipped to the edge.
	EXPECT_GT(atEdgePadded, atEdgePlain);
}

TEST_F(CascadeDetection, ClassesInParallelGiveTheSameCandidates)
{
	// threads = 0 (all cores; each class, and each range-gated pass of a
	// class, on its own thread) against one thread: the same candidates in
	// the same order, on every sweep.
	const Simulated& s = scene();
	PerceptionPipeline p;
	opts.threads = 1;
	CascadeDetector one(opts);
	opts.threads = 0;
	CascadeDetector all(opts);
	std::size_t accepted = 0, supported = 0;
	for (const Sweep& sw : s.sweeps)
	{
		const LabeledSweep ls = p.process(sw);
		const auto run = [&](CascadeDetector& d)
		{ return candidatesOf(d, sw, ls); };
		const auto a = run(one), b = run(all);
		ASSERT_EQ(a.size(), b.size());
		for (std::size_t j = 0; j < a.size(); j++)
		{
			EXPECT_EQ(a[j].label, b[j].label);
			EXPECT_EQ(a[j].box, b[j].box);
			EXPECT_EQ(a[j].neighbours, b[j].neighbours);
			EXPECT_EQ(a[j].cascadeSupport, b[j].cascadeSupport);
			EXPECT_EQ(a[j].accepted, b[j].accepted);
			EXPECT_EQ(a[j].rejection, b[j].rejection);
			EXPECT_DOUBLE_EQ(a[j].shapeScore, b[j].shapeScore);
			accepted += a[j].accepted;
			// A segment is described while the cascades run; its shape
			// still carries the support the cascades gave it.
			for (const auto* c : {&a[j], &b[j]})
				if (c->shape && opts.classOptions(c->label).cascadeSupport)
				{
					EXPECT_EQ(
					    (*c->shape)[ObjectShape::kCascadeSupport],
					    float(c->cascadeSupport));
					supported += c->fromSegment && c->cascadeSupport > 0;
				}
		}
	}
	EXPECT_GT(accepted, 10u) << "the scene's objects are found";
	EXPECT_GT(supported, 0u) << "segments with cascade support were described";
}

TEST_F(CascadeDetection, SearchAloneGivesTheCascadeBoxesOfTheCandidates)
{
	// searchCascades (the bench's search alone) on prepareSearch's images:
	// per class, the boxes and neighbour counts of detectCandidates' cascade
	// candidates, in their order, on every sweep and on both cores.
	const Simulated& s = scene();
	PerceptionPipeline p;
	CascadeDetector d(opts);
	std::size_t boxes = 0;
	for (const Sweep& sw : s.sweeps)
	{
		const LabeledSweep ls = p.process(sw);
		const auto cands = candidatesOf(d, sw, ls);
		const auto in = d.prepareSearch(
		    sw.phis(), sw.thetas(), ls.normals, ls.normalMask, ls.points,
		    ls.groundZ, ls.labels, ls.areaIds, false);
		EXPECT_TRUE(in.segments.empty());
		const auto found = d.searchCascades(in);
		ASSERT_EQ(found.size(), opts.classes.size());
		for (std::size_t i = 0; i < found.size(); i++)
		{
			std::vector<const CascadeDetector::Candidate*> ofClass;
			for (const auto& c : cands)
				if (c.label == opts.classes[i].label && !c.fromSegment)
					ofClass.push_back(&c);
			ASSERT_EQ(ofClass.size(), found[i].boxes.size());
			ASSERT_EQ(found[i].neighbours.size(), found[i].boxes.size());
			for (std::size_t j = 0; j < ofClass.size(); j++)
			{
				EXPECT_EQ(ofClass[j]->box, found[i].boxes[j]);
				EXPECT_EQ(ofClass[j]->neighbours, found[i].neighbours[j]);
			}
			boxes += found[i].boxes.size();
		}
		EXPECT_GT(d.lastTimings().cascades, 0.0);
	}
	EXPECT_GT(boxes, 20u) << "the cascades fire on the scene";
}

TEST_F(CascadeDetection, SegmentCandidatesReachObjectsTheWindowsMiss)
{
	// Without the shape check, the ground-truth objects some candidate of
	// their class measures (passes the size check, IoU >= 0.3): the 3D
	// segments add objects to the cascade's, and lose none of them.
	const Simulated& s = scene();
	PerceptionPipeline p;
	for (auto& k : opts.classes)
	{
		k.shapeModel.clear();
		k.segmentCandidates = false;
	}
	CascadeDetector windows(opts);
	for (auto& k : opts.classes) k.segmentCandidates = true;
	CascadeDetector segments(opts);
	const std::vector<Label> labels{
	    Label::Washbasin, Label::Wastebasket, Label::Stairs};
	std::size_t reachedByWindows = 0, reachedWithSegments = 0, fromSegment = 0;
	for (std::size_t i = 0; i < s.sweeps.size(); i++)
	{
		const Sweep& sw = s.sweeps[i];
		const LabeledSweep ls = p.process(sw);
		const auto reached = [&](CascadeDetector& d)
		{
			const auto cands = candidatesOf(d, sw, ls);
			std::set<std::pair<Label, int>> out;
			for (const auto& c : cands)
			{
				if (c.fromSegment)
				{
					fromSegment++;
					EXPECT_EQ(c.neighbours, 0);
				}
				if (!c.measure || c.rejection.rfind("too", 0) == 0) continue;
				for (const auto& g : GroundTruthObject::fromLabelImage(
				         s.groundTruth[i], labels))
					if (g.pixels >= 150 && g.label == c.label &&
					    ObjectScorer::iou(c.measure->box, g.box) >= 0.3)
						out.insert({g.label, g.instance});
			}
			return out;
		};
		const auto a = reached(windows), b = reached(segments);
		for (const auto& o : a) EXPECT_TRUE(b.count(o)) << "sweep " << i;
		reachedByWindows += a.size();
		reachedWithSegments += b.size();
	}
	std::printf(
	    "objects reached by windows %zu, with segments %zu (%zu segment "
	    "candidates)\n",
	    reachedByWindows, reachedWithSegments, fromSegment);
	EXPECT_GT(fromSegment, 0u);
	EXPECT_GT(reachedWithSegments, reachedByWindows);
}

TEST_F(CascadeDetection, MinSeparationKeepsTheFirstRankedOfNearbyDetections)
{
	// With a separation wider than the room, each class keeps one accepted
	// detection per sweep: the one with the highest shape score, then the
	// most neighbours, then points, of those accepted without it; its box
	// and pixels take in theirs.
	const Simulated& s = scene();
	PerceptionPipeline p;
	const auto all = detectorWith(
	    opts,
	    [](auto& k)
	    {
		    k.minSeparation = 0;
		    k.grow = 0;
	    });
	const auto one = detectorWith(
	    opts,
	    [](auto& k)
	    {
		    k.minSeparation = 100;
		    k.grow = 0;
	    });
	std::size_t removed = 0;
	for (std::size_t i = 0; i < s.sweeps.size(); i++)
	{
		const Sweep& sw = s.sweeps[i];
		const LabeledSweep ls = p.process(sw);
		const auto a = candidatesOf(*all, sw, ls),
		           b = candidatesOf(*one, sw, ls);
		ASSERT_EQ(a.size(), b.size());
		for (const auto& k : opts.classes)
		{
			const CascadeDetector::Candidate* best = nullptr;
			std::size_t accepted = 0;
			for (std::size_t j = 0; j < a.size(); j++)
			{
				if (a[j].label != k.label) continue;
				EXPECT_FALSE(b[j].accepted && !a[j].accepted) << "sweep " << i;
				accepted += b[j].accepted;
				if (!a[j].accepted) continue;
				removed += !b[j].accepted;
				const auto rank = [](const CascadeDetector::Candidate& c) {
					return std::make_tuple(
					    c.shapeScore, c.neighbours, c.measure->points);
				};
				if (!best || rank(a[j]) > rank(*best)) best = &a[j];
			}
			EXPECT_EQ(accepted, best ? 1u : 0u) << "sweep " << i;
			if (!best) continue;
			const auto& kept = b[std::size_t(best - a.data())];
			EXPECT_TRUE(kept.accepted) << "sweep " << i;
			std::size_t pixels = 0;
			for (const auto& c : a)
				if (c.label == k.label && c.accepted)
				{
					EXPECT_EQ(
					    kept.measure->box & c.measure->box, c.measure->box)
					    << "sweep " << i;
					pixels += c.measure->pixels.size();
				}
			EXPECT_EQ(kept.measure->pixels.size(), pixels) << "sweep " << i;
		}
	}
	std::printf("%zu accepted detections merged into nearby ones\n", removed);
	EXPECT_GT(removed, 0u);
}

TEST_F(CascadeDetection, GrowTakesInTheRestOfAnAcceptedFlight)
{
	// grow_m changes no decision, score or centroid; it only moves the
	// boxes (and pixels) of accepted stairs over the flight around them,
	// and no flight a box matched is lost.
	const Simulated& s = scene();
	PerceptionPipeline p;
	const auto none = detectorWith(opts, [](auto& k) { k.grow = 0; });
	const auto grown = detectorWith(
	    opts, [](auto& k) { k.grow = k.label == Label::Stairs ? 0.3 : 0; });
	double iouBefore = 0, iouAfter = 0;
	std::size_t changed = 0, accepted = 0, matchedBefore = 0, matchedAfter = 0;
	for (std::size_t i = 0; i < s.sweeps.size(); i++)
	{
		const Sweep& sw = s.sweeps[i];
		const LabeledSweep ls = p.process(sw);
		const auto a = candidatesOf(*none, sw, ls),
		           b = candidatesOf(*grown, sw, ls);
		ASSERT_EQ(a.size(), b.size());
		const auto flights = GroundTruthObject::fromLabelImage(
		    s.groundTruth[i], {Label::Stairs});
		for (std::size_t j = 0; j < a.size(); j++)
		{
			ASSERT_EQ(a[j].accepted, b[j].accepted) << "sweep " << i;
			EXPECT_EQ(a[j].shapeScore, b[j].shapeScore) << "sweep " << i;
			if (!a[j].accepted) continue;
			EXPECT_EQ(a[j].measure->centroid, b[j].measure->centroid);
			if (a[j].label != Label::Stairs)
			{
				EXPECT_EQ(a[j].measure->box, b[j].measure->box);
				continue;
			}
			accepted++;
			changed += a[j].measure->box != b[j].measure->box;
			for (const auto& g : flights)
			{
				const double before =
				                 ObjectScorer::iou(a[j].measure->box, g.box),
				             after =
				                 ObjectScorer::iou(b[j].measure->box, g.box);
				iouBefore += before;
				iouAfter += after;
				matchedBefore += before >= 0.3;
				matchedAfter += after >= 0.3;
			}
		}
	}
	std::printf(
	    "%zu of %zu accepted flights grown; summed IoU with the true "
	    "flights %.2f -> %.2f, IoU >= 0.3 %zu -> %zu\n",
	    changed, accepted, iouBefore, iouAfter, matchedBefore, matchedAfter);
	EXPECT_GT(changed, 0u);
	EXPECT_GE(matchedAfter, matchedBefore);
}

TEST_F(CascadeDetection, ShapeTrainingLearnsEachCandidateByItsOwnBox)
{
	// The forest learns the candidates before any growth: the shipped
	// grow_m (or any other) gives the same samples, so that
	// scripts/train-cascades reproduces the shipped forests.
	const auto dir = std::filesystem::temp_directory_path() /
	                 ("semnav_shape_training_" + std::to_string(::getpid()));
	const Scene sc = SceneLoader::loadFile(
	    test::kSourceDir + "/datasets/cascade-scenes/test_c.yaml");
	SimulationRunner(sc, SimulationRunner::TOptions(), 1).run(dir.string());
	ShapeTraining::Params params;
	params.grids = false;
	params.steps = true;
	const auto samplesWith = [&](double grow)
	{
		CascadeDetector::TOptions o = opts;
		for (auto& k : o.classes) k.grow = grow;
		return ShapeTraining::collect({dir.string()}, o, Label::Stairs, params);
	};
	const auto shipped = samplesWith(2.0), none = samplesWith(0);
	std::filesystem::remove_all(dir);
	ASSERT_GT(shipped.objects, 0u);
	ASSERT_EQ(shipped.features.size(), none.features.size());
	EXPECT_EQ(cv::norm(shipped.features, none.features, cv::NORM_INF), 0);
	EXPECT_EQ(cv::countNonZero(shipped.isObject != none.isObject), 0);
}
