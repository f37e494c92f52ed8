/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <semnav/cascade/CascadeError.h>
#include <semnav/cascade/CascadeEvaluator.h>
#include <semnav/cascade/CascadeTrainer.h>
#include <semnav/cascade/CascadeXml.h>
#include <semnav/common/Error.h>

#include <opencv2/objdetect.hpp>

#include "../common/SavedAndLoaded.h"
#include "CascadeTestUtils.h"

using namespace semnav;

namespace
{
struct Trained
{
	std::vector<cv::Mat> pos;
	std::vector<NegativeImage> neg;
	HaarCascade cascade;
	CascadeTrainer::Report report;
	std::string xml;
};

Trained train(uint64_t seed, int threads, int stages = 4)
{
	Trained t;
	test::syntheticTrainingSet({12, 12}, 200, t.pos, t.neg);
	auto o = test::tinyTrainerOptions();
	o.threads = threads;
	o.numStages = stages;
	CascadeTrainer tr(o);
	t.cascade = tr.train(t.pos, t.neg, seed);
	t.report = tr.report();
	t.xml = CascadeXml::toString(t.cascade);
	return t;
}

const Trained& reference()
{
	static const Trained t = train(42, 0);
	return t;
}
}  // namespace

TEST(CascadeTrainer, EachStageMeetsItsHitRateOnItsPositives)
{
	const Trained& t = reference();
	ASSERT_GE(t.cascade.stages.size(), 2u) << t.report.stopReason;
	ASSERT_EQ(t.report.stages.size(), t.cascade.stages.size());
	// Through the XML, as a detector would load it.
	const HaarCascade loaded = CascadeXml::fromString(t.xml);
	CascadeEvaluator ev(loaded);
	for (std::size_t s = 0; s < loaded.stages.size(); s++)
	{
		const auto& rep = t.report.stages[s];
		ASSERT_FALSE(rep.positiveIndices.empty());
		std::size_t pass = 0, passCv = 0;
		// The stage alone, also in cv::CascadeClassifier.
		HaarCascade only = loaded;
		only.stages = {loaded.stages[s]};
		const std::string onlyXml = CascadeXml::toString(only);
		cv::FileStorage fs(
		    onlyXml, cv::FileStorage::READ | cv::FileStorage::MEMORY);
		cv::CascadeClassifier cc;
		ASSERT_TRUE(cc.read(fs.getFirstTopLevelNode()));
		for (int i : rep.positiveIndices)
		{
			ev.setImage(t.pos[i]);
			const auto r = ev.evaluateStages({0, 0}, s, 1);
			pass += r.stage == static_cast<int>(s + 1);
			std::vector<cv::Rect> found;
			cc.detectMultiScale(
			    t.pos[i], found, 1.1, 0, 0, t.cascade.windowSize,
			    t.cascade.windowSize);
			passCv += found.size();
		}
		const double hit = double(pass) / double(rep.positiveIndices.size());
		EXPECT_GE(hit, 0.995) << "stage " << s;
		EXPECT_DOUBLE_EQ(hit, rep.hitRate) << "stage " << s;
		EXPECT_EQ(passCv, pass) << "stage " << s << " in OpenCV";
		EXPECT_LE(rep.falseAlarm, 0.5 + 1e-12) << "stage " << s;
		EXPECT_GT(rep.negatives, 0u);
	}
	// Negatives get rarer stage by stage.
	EXPECT_LT(
	    t.report.stages.back().acceptanceRatio,
	    t.report.stages.front().acceptanceRatio);
}

TEST(CascadeTrainer, SameSeedSameXmlWhateverTheThreads)
{
	const Trained one = train(42, 1);
	EXPECT_EQ(one.xml, reference().xml);
	const Trained other = train(43, 2);
	EXPECT_NE(other.xml, reference().xml);
}

TEST(CascadeTrainer, CalibrationPositivesSetTheStageThresholds)
{
	Trained t;
	test::syntheticTrainingSet({12, 12}, 200, t.pos, t.neg);
	auto o = test::tinyTrainerOptions();
	o.numStages = 4;
	o.calibrationFraction = 0.3;
	CascadeTrainer tr(o);
	const HaarCascade c = tr.train(t.pos, t.neg, 42);
	const auto& rep = tr.report();
	ASSERT_GE(c.stages.size(), 2u) << rep.stopReason;
	for (std::size_t s = 0; s < c.stages.size(); s++)
	{
		const auto& r = rep.stages[s];
		// About 30 % held out, none of them boosted on.
		EXPECT_GT(r.calibrationPositives, 30u) << "stage " << s;
		EXPECT_LT(r.calibrationPositives, r.positives) << "stage " << s;
		// The threshold keeps the hit rate on both sets.
		EXPECT_GE(r.calibrationHitRate, o.minHitRate) << "stage " << s;
		EXPECT_GE(r.hitRate, o.minHitRate) << "stage " << s;
		EXPECT_LE(r.falseAlarm, o.maxFalseAlarm + 1e-12) << "stage " << s;
	}
	// Same seed, same cascade; not the one trained without calibration.
	CascadeTrainer again(o);
	EXPECT_EQ(
	    CascadeXml::toString(again.train(t.pos, t.neg, 42)),
	    CascadeXml::toString(c));
	EXPECT_NE(CascadeXml::toString(c), reference().xml);
}

TEST(CascadeTrainer, RangeGateChoosesTheNegativeWindows)
{
	// A range gate that lets every window through: the same cascade as
	// without one.
	Trained t;
	test::syntheticTrainingSet({12, 12}, 200, t.pos, t.neg);
	for (auto& n : t.neg)
		n.range = cv::Mat(n.image.size(), CV_32F, cv::Scalar(2.0));
	auto o = test::tinyTrainerOptions();
	o.threads = 0;
	o.numStages = 4;
	CascadeTrainer tr(o);
	EXPECT_EQ(
	    CascadeXml::toString(tr.train(t.pos, t.neg, 42)), reference().xml);
	// Objects of at most 1 m: a window of side s at 2 m holds one of
	// 2 s / perSide m, so with perSide 24 windows up to 12 pixels, the
	// first pyramid level, are negatives; the others are not searched.
	for (auto& n : t.neg)
	{
		n.gate.perSide = 24;
		n.gate.hi = 1.0;
	}
	CascadeTrainer small(o);
	small.train(t.pos, t.neg, 42);
	EXPECT_LT(
	    small.report().stages.front().negativeWindows,
	    tr.report().stages.front().negativeWindows);
	// None: no negative window at all.
	for (auto& n : t.neg) n.gate.hi = 0.1;
	EXPECT_THROW(CascadeTrainer(o).train(t.pos, t.neg, 42), CascadeError);
}

TEST(CascadeTrainer, RejectsUnusableInput)
{
	CascadeTrainer tr(test::tinyTrainerOptions());
	std::vector<cv::Mat> pos;
	std::vector<NegativeImage> neg;
	test::syntheticTrainingSet({12, 12}, 20, pos, neg);
	EXPECT_THROW(tr.train({}, neg, 1), CascadeError);
	EXPECT_THROW(
	    tr.train({cv::Mat(12, 12, CV_8UC1, cv::Scalar(9))}, neg, 1),
	    CascadeError);  // no contrast
	EXPECT_THROW(tr.train({cv::Mat(10, 12, CV_8UC1)}, neg, 1), CascadeError);
	EXPECT_THROW(tr.train(pos, {}, 1), CascadeError);
	EXPECT_THROW(
	    tr.train(pos, {{cv::Mat(5, 5, CV_8UC1, cv::Scalar(1)), {}}}, 1),
	    CascadeError);
}

TEST(CascadeTrainer, OptionsLoadSaveAndErrors)
{
	CascadeTrainer::TOptions o;
	mrpt::config::CConfigFileMemory c(
	    "[T]\nnum_stages = 7\nfeature_mode = core\nmin_hit_rate = 0.99\n"
	    "calibration_fraction = 0.25\n");
	o.loadFromConfigFile(c, "T");
	EXPECT_EQ(o.numStages, 7);
	EXPECT_EQ(o.mode, HaarMode::Core);
	EXPECT_DOUBLE_EQ(o.minHitRate, 0.99);
	CascadeTrainer::TOptions back = test::savedAndLoaded(o, "T");
	EXPECT_EQ(back.numStages, 7);
	EXPECT_EQ(back.mode, HaarMode::Core);
	EXPECT_DOUBLE_EQ(back.calibrationFraction, 0.25);
	mrpt::config::CConfigFileMemory bad1("[T]\nnum_stagez = 7\n");
	EXPECT_THROW(o.loadFromConfigFile(bad1, "T"), ConfigError);
	mrpt::config::CConfigFileMemory bad2("[T]\nmax_false_alarm = 1.5\n");
	EXPECT_THROW(o.loadFromConfigFile(bad2, "T"), ConfigError);
	mrpt::config::CConfigFileMemory bad3("[T]\nfeature_mode = diagonal\n");
	EXPECT_THROW(o.loadFromConfigFile(bad3, "T"), ConfigError);
	mrpt::config::CConfigFileMemory bad4("[T]\ncalibration_fraction = 1\n");
	EXPECT_THROW(o.loadFromConfigFile(bad4, "T"), ConfigError);
}
