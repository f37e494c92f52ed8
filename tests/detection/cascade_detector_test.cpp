/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <semnav/cascade/CascadeError.h>
#include <semnav/common/Error.h>
#include <semnav/detection/CascadeDetector.h>
#include <semnav/training/CascadeTraining.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>

#include "../TestPaths.h"
#include "../common/SavedAndLoaded.h"

using namespace semnav;

namespace
{

/** Points of a 40 x 60 sweep patch: a wall 3 m ahead (x = 3), a box
 * 0.4 m wide, 0.84 m high at x = 2 in rows/cols [20, 40) x [20, 40),
 * floor in the lowest rows. */
cv::Mat scene(cv::Mat& labels)
{
	cv::Mat p(40, 60, CV_32FC3);
	labels = cv::Mat(40, 60, CV_8U, cv::Scalar(static_cast<int>(Label::Wall)));
	for (int r = 0; r < 40; r++)
		for (int c = 0; c < 60; c++)
		{
			const float y = 0.02f * (30 - c);  // left positive
			if (r < 5)
			{
				p.at<cv::Vec3f>(r, c) = {1.5f + 0.1f * r, y, 0.0f};
				labels.at<uint8_t>(r, c) = static_cast<uint8_t>(Label::Floor);
			}
			else if (r >= 20 && c >= 20 && c < 40)
			{
				const float z = 0.04f * (r - 18);  // 0.08 .. 0.84
				p.at<cv::Vec3f>(r, c) = {2.0f, y, z};
				labels.at<uint8_t>(r, c) =
				    static_cast<uint8_t>(Label::Obstacle);
			}
			else
				p.at<cv::Vec3f>(r, c) = {3.0f, y, 0.04f * r};
		}
	return p;
}
}  // namespace

TEST(CascadeDetector, MeasureSeparatesObjectFromFloorAndWall)
{
	cv::Mat labels;
	const cv::Mat pts = scene(labels);
	std::vector<cv::Point> all, centre;
	for (int r = 0; r < 40; r++)
		for (int c = 10; c < 50; c++)
		{
			all.emplace_back(c, r);
			if (r >= 20 && c >= 25 && c < 35) centre.emplace_back(c, r);
		}
	// With the rule labels: the wall is excluded by label and depth.
	const auto m =
	    CascadeDetector::measure(pts, labels, all, centre, 0.0, 0.04, 0.5, 10);
	ASSERT_TRUE(m.has_value());
	EXPECT_EQ(m->box, cv::Rect(20, 20, 20, 20));
	EXPECT_EQ(m->points, 400u);
	EXPECT_NEAR(m->width, 0.34, 0.021);  // 5th..95th percentile
	EXPECT_NEAR(m->top, 0.82, 0.021);
	EXPECT_NEAR(m->centroid.x, 2.0, 1e-6);
	// Without labels, depth alone keeps the wall out (1 m behind).
	const auto d = CascadeDetector::measure(
	    pts, cv::Mat(), all, centre, 0.0, 0.04, 0.5, 10);
	ASSERT_TRUE(d.has_value());
	EXPECT_EQ(d->points, 400u);
	// A deep tolerance takes the wall too.
	const auto w = CascadeDetector::measure(
	    pts, cv::Mat(), all, centre, 0.0, 0.04, 2.0, 10);
	EXPECT_GT(w->points, 400u);
	// Unless the wall behind is cut off (it is 0.7 m long in the patch).
	const auto cut = CascadeDetector::measure(
	    pts, cv::Mat(), all, centre, 0.0, 0.04, 2.0, 10, false, 0.5);
	ASSERT_TRUE(cut.has_value());
	EXPECT_EQ(cut->points, 400u);
	EXPECT_EQ(cut->box, cv::Rect(20, 20, 20, 20));
	// A range window keeps the points at its ranges only: the object (2 m)
	// or the wall (3 m) whatever the centre holds.
	const auto near = CascadeDetector::measure(
	    pts, cv::Mat(), all, centre, 0.0, 0.04, 2.0, 10, false, 0, 1.8, 2.2);
	ASSERT_TRUE(near.has_value());
	EXPECT_EQ(near->points, 400u);
	EXPECT_EQ(near->box, cv::Rect(20, 20, 20, 20));
	const auto far = CascadeDetector::measure(
	    pts, cv::Mat(), all, centre, 0.0, 0.04, 2.0, 10, false, 0, 2.5, 3.5);
	ASSERT_TRUE(far.has_value());
	EXPECT_EQ(far->points, 35u * 40u - 400u);
	EXPECT_NEAR(far->centroid.x, 3.0, 1e-6);
	// Too few points.
	EXPECT_FALSE(
	    CascadeDetector::measure(pts, labels, all, centre, 0.0, 0.04, 0.5, 500)
	        .has_value());
}

TEST(CascadeDetector, ContinuingShareFindsTheLowerPartOfSomethingTaller)
{
	// A 20 x 20 pixel object 2 m ahead, 1.7 cm per row (z 0.34 at its top
	// row 19), and the 10 rows above it: the same face going on up in
	// columns < split (a pillar the rules call wall), a wall 1 m behind in
	// the others.
	const auto share = [](int split, Label above)
	{
		cv::Mat p(30, 20, CV_32FC3), labels(30, 20, CV_8U);
		CascadeDetector::Measure m;
		for (int r = 0; r < 30; r++)
			for (int c = 0; c < 20; c++)
			{
				const float y = 0.02f * (10 - c), z = 0.017f * float(r);
				const bool object = r < 20, pillar = c < split;
				p.at<cv::Vec3f>(r, c) = {object || pillar ? 2.0f : 3.0f, y, z};
				labels.at<uint8_t>(r, c) = static_cast<uint8_t>(
				    object   ? Label::Obstacle
				    : pillar ? above
				             : Label::Wall);
				if (object) m.pixels.emplace_back(c, r);
			}
		m.box = cv::Rect(0, 0, 20, 20);
		return CascadeDetector::continuingShare(p, labels, m);
	};
	EXPECT_DOUBLE_EQ(share(0, Label::Wall), 0.0);
	EXPECT_DOUBLE_EQ(share(20, Label::Wall), 1.0);
	EXPECT_DOUBLE_EQ(share(5, Label::Wall), 0.25);
	// Points above that are ceiling do not count.
	EXPECT_DOUBLE_EQ(share(20, Label::Ceiling), 0.0);
}

TEST(CascadeDetector, OverheadShareFindsFoliageOverAPot)
{
	// A pot: 20 x 20 pixels 2 m ahead, 0.4 m wide, 1.7 cm per row (top 0.32
	// m at row 19); in the 20 rows above it either foliage overhanging it
	// (0.1 m nearer, over columns < split), a wall 0.1 m behind it, or the
	// ceiling's label on the foliage.
	const auto share = [](int split, Label above, float foliageX)
	{
		cv::Mat p(40, 20, CV_32FC3), labels(40, 20, CV_8U);
		CascadeDetector::Measure m;
		for (int r = 0; r < 40; r++)
			for (int c = 0; c < 20; c++)
			{
				const float y = 0.02f * (10 - c), z = 0.017f * float(r);
				const bool object = r < 20, foliage = !object && c < split;
				p.at<cv::Vec3f>(r, c) = {
				    object    ? 2.0f
				    : foliage ? foliageX
				              : 2.1f,
				    y, z};
				labels.at<uint8_t>(r, c) = static_cast<uint8_t>(
				    object    ? Label::Obstacle
				    : foliage ? above
				              : Label::Wall);
				if (object) m.pixels.emplace_back(c, r);
			}
		m.box = cv::Rect(0, 0, 20, 20);
		m.top = 0.017 * 19;
		m.width = 0.4;
		m.centroid = {2.0, 0.0, 0.16};
		return CascadeDetector::overheadShare(p, labels, m, 0.0);
	};
	EXPECT_DOUBLE_EQ(share(20, Label::Obstacle, 1.9f), 1.0);
	EXPECT_DOUBLE_EQ(share(10, Label::Obstacle, 1.9f), 0.5);
	// Only a wall behind: nothing overhead.
	EXPECT_DOUBLE_EQ(share(0, Label::Obstacle, 1.9f), 0.0);
	// Something above but not in front of the object's face, or far in
	// front of it, or the ceiling: not over it.
	EXPECT_DOUBLE_EQ(share(20, Label::Obstacle, 2.0f), 0.0);
	EXPECT_DOUBLE_EQ(share(20, Label::Obstacle, 1.0f), 0.0);
	EXPECT_DOUBLE_EQ(share(20, Label::Ceiling, 1.9f), 0.0);
}

TEST(CascadeDetector, FlatFaceShareTellsABasinFromFoliage)
{
	// The top band (rows 0-9, 0.8-0.9 m high) of an object 2 m ahead seen
	// in 30 columns 2 cm apart across the line of sight: `depth(y)` is how
	// far behind x = 2 m its front lies there. Below the band (rows 10-19,
	// 0.5 m) a pedestal that must not count.
	const auto share =
	    [](const std::function<double(double)>& depth, int columns = 30)
	{
		cv::Mat p(20, columns, CV_32FC3);
		CascadeDetector::Measure m;
		for (int r = 0; r < 20; r++)
			for (int c = 0; c < columns; c++)
			{
				const double y = 0.02 * (c - (columns - 1) / 2.0);
				const bool band = r < 10;
				// A little noise, alternating by row.
				const double x = 2.0 + (band ? depth(y) : 0.3 * y * y) +
				                 ((r + c) % 2 ? 0.002 : -0.002);
				p.at<cv::Vec3f>(r, c) = cv::Vec3f(
				    float(x), float(y), band ? 0.9f - 0.01f * r : 0.5f);
				m.pixels.emplace_back(c, r);
			}
		m.box = cv::Rect(0, 0, columns, 20);
		m.top = 0.9;
		return CascadeDetector::flatFaceShare(p, m, 0.0);
	};
	// A basin's flat front, seen head on or turned 30 deg: every direction
	// along one face.
	EXPECT_DOUBLE_EQ(share([](double) { return 0.0; }).value(), 1.0);
	EXPECT_DOUBLE_EQ(
	    share([](double y) { return std::tan(M_PI / 6) * y; }).value(), 1.0);
	// Seen across its corner (two faces at 45 deg to the line of sight):
	// the faces are one direction folded; only the corner's may differ.
	EXPECT_GE(share([](double y) { return std::abs(y); }).value(), 0.9);
	// Foliage: a cylinder 0.3 m in radius, its front spread over +-60 deg.
	const auto foliage =
	    share([](double y) { return 0.3 - std::sqrt(0.09 - y * y); }, 27);
	ASSERT_TRUE(foliage.has_value());
	EXPECT_LT(*foliage, 0.6);
	// Too few directions measured (3 columns): nothing to tell.
	EXPECT_FALSE(share([](double) { return 0.0; }, 3).has_value());
}

TEST(CascadeDetector, PassesCoverNearAndFarObjects)
{
	CascadeDetector::TClassOptions k(Label::Wastebasket);
	k.upscale = 1;
	k.farUpscale = 3;
	k.farBelowPx = 24;
	k.farMinElevation = -16 * M_PI / 180;
	k.farMaxElevation = 8 * M_PI / 180;
	const auto p = k.passes(211, -15 * M_PI / 180, 90 * M_PI / 180, {20, 20});
	ASSERT_EQ(p.size(), 2u);
	EXPECT_DOUBLE_EQ(p[0].upscale, 1);
	EXPECT_EQ(p[0].rowBegin, 0);
	EXPECT_EQ(p[0].rowEnd, 211);
	EXPECT_DOUBLE_EQ(p[0].minSide, 24);
	EXPECT_DOUBLE_EQ(p[1].upscale, 3);
	EXPECT_EQ(p[1].rowBegin, 0);  // -16 deg is below the sweep
	EXPECT_EQ(p[1].rowEnd, 47);   // 8 deg = row 46
	EXPECT_NEAR(p[1].minSide, 20.0 / 3, 1e-12);
	EXPECT_DOUBLE_EQ(p[1].maxSide, 24);
	EXPECT_EQ(&DetectionPass::forSide(p, 10), &p[1]);
	EXPECT_EQ(&DetectionPass::forSide(p, 30), &p[0]);
	EXPECT_EQ(&DetectionPass::forSide(p, 3), &p[1]);
	// Box mapping of a pass.
	EXPECT_EQ(
	    p[1].toImage(p[1].toPass({30, 20, 9, 12})), cv::Rect(30, 20, 9, 12));
}

TEST(CascadeDetector, ShippedConfigLoads)
{
	const auto o = CascadeDetector::TOptions::fromIniFile(
	    test::kSourceDir + "/config/cascade.ini");
	ASSERT_EQ(o.classes.size(), 3u);
	EXPECT_EQ(o.classes[0].label, Label::Washbasin);
	EXPECT_EQ(o.classes[1].label, Label::Wastebasket);
	EXPECT_EQ(o.classes[2].label, Label::Stairs);
	EXPECT_EQ(
	    std::filesystem::path(o.cascadePath(o.classes[1])).lexically_normal(),
	    std::filesystem::path(
	        test::kSourceDir + "/datasets/cascades/wastebasket.xml")
	        .lexically_normal());
	const auto t = CascadeTraining::TOptions::fromIniFile(
	    test::kSourceDir + "/config/cascade.ini");
	EXPECT_EQ(t.trainer.windowWidth, 20);
	EXPECT_EQ(t.trainer.mode, HaarMode::All);
	EXPECT_DOUBLE_EQ(t.trainer.minHitRate, 0.995);
	EXPECT_DOUBLE_EQ(t.trainer.maxFalseAlarm, 0.5);
	EXPECT_TRUE(o.rangeScales);
	EXPECT_EQ(o.classes[2].windowStep, 2);
	// Every class takes segment candidates and weighs cascade support (their
	// forests were trained so); stairs measured 0.3 m wide stay candidates.
	for (std::size_t k : {0, 1, 2})
	{
		EXPECT_TRUE(o.classes[k].segmentCandidates);
		EXPECT_TRUE(o.classes[k].cascadeSupport);
	}
	EXPECT_DOUBLE_EQ(o.classes[2].minWidth, 0.3);
	// Washbasins and wastebaskets need 100 object points (ground truth
	// counts an object from 150 pixels; fewer were slivers of one).
	EXPECT_EQ(o.classes[0].minPoints, 100);
	EXPECT_EQ(o.classes[1].minPoints, 100);
	EXPECT_EQ(o.classes[2].minPoints, 15);
	// Washbasin and stairs forests were trained with the back wall cut off;
	// the wastebasket's without (it did worse with).
	EXPECT_DOUBLE_EQ(o.classes[0].backWallLength, 0.8);
	EXPECT_DOUBLE_EQ(o.classes[1].backWallLength, 0);
	EXPECT_DOUBLE_EQ(o.classes[2].backWallLength, 0.8);
	EXPECT_DOUBLE_EQ(o.classes[0].maxContinuingShare, 0.3);
	EXPECT_DOUBLE_EQ(o.classes[1].maxContinuingShare, 1);
	EXPECT_DOUBLE_EQ(o.classes[2].maxContinuingShare, 1);
	// Wastebaskets: not under foliage (a plant pot, generated scenes).
	EXPECT_DOUBLE_EQ(o.classes[0].maxOverheadShare, 1);
	EXPECT_DOUBLE_EQ(o.classes[1].maxOverheadShare, 0.7);
	EXPECT_DOUBLE_EQ(o.classes[2].maxOverheadShare, 1);
	// Washbasins: a flat-faced top (not a plant's round foliage).
	EXPECT_DOUBLE_EQ(o.classes[0].minFlatFaceShare, 0.6);
	EXPECT_DOUBLE_EQ(o.classes[1].minFlatFaceShare, 0);
	EXPECT_DOUBLE_EQ(o.classes[2].minFlatFaceShare, 0);
	// Stairs beside the robot (70 deg or more) need a shape score of 0.45,
	// elsewhere 0.3; the other classes have no stricter side check.
	EXPECT_DOUBLE_EQ(o.classes[2].minShapeScoreAt(0.0), 0.3);
	EXPECT_DOUBLE_EQ(o.classes[2].minShapeScoreAt(-69 * M_PI / 180), 0.3);
	EXPECT_DOUBLE_EQ(o.classes[2].minShapeScoreAt(-70 * M_PI / 180), 0.45);
	EXPECT_DOUBLE_EQ(o.classes[2].minShapeScoreAt(88 * M_PI / 180), 0.45);
	EXPECT_DOUBLE_EQ(o.classes[0].minShapeScoreAt(88 * M_PI / 180), 0.4);
	EXPECT_DOUBLE_EQ(o.classes[1].minShapeScoreAt(88 * M_PI / 180), 0.4);
	EXPECT_DOUBLE_EQ(o.classes[0].minSeparation, 0);
	EXPECT_DOUBLE_EQ(o.classes[2].minSeparation, 2.0);
	EXPECT_DOUBLE_EQ(o.classes[0].grow, 0);
	EXPECT_DOUBLE_EQ(o.classes[2].grow, 0.3);
	// Stairs boxes are grouped (every raw window a candidate let the box
	// with the most points win among duplicates); no wastebasket far pass.
	EXPECT_EQ(o.classes[2].minNeighbors, 8);
	EXPECT_DOUBLE_EQ(o.classes[1].farUpscale, 0);
	// A class's [SampleGenerator.<label>] changes only that class.
	const auto dir = std::filesystem::temp_directory_path() /
	                 ("semnav_cascade_ini_" + std::to_string(::getpid()));
	std::filesystem::create_directories(dir);
	const auto ini = (dir / "c.ini").string();
	{
		std::ofstream f(ini);
		f << "[SampleGenerator]\npositives = 50\n"
		     "[SampleGenerator.stairs]\nrange_negatives = true\n";
	}
	const auto pc = CascadeTraining::TOptions::fromIniFile(ini);
	EXPECT_TRUE(pc.samplesFor(Label::Stairs).rangeNegatives);
	EXPECT_EQ(pc.samplesFor(Label::Stairs).positives, 50);
	EXPECT_FALSE(pc.samplesFor(Label::Washbasin).rangeNegatives);
	std::filesystem::remove_all(dir);
}

TEST(CascadeDetector, OptionErrorsNameSectionAndKey)
{
	const auto load = [](const std::string& text)
	{
		mrpt::config::CConfigFileMemory c(text);
		CascadeDetector::TOptions o;
		o.loadFromConfigFile(c, "CascadeDetector");
		return o;
	};
	EXPECT_EQ(load("[CascadeDetector]\nclasses = stairs\n").classes.size(), 1u);
	try
	{
		load(
		    "[CascadeDetector]\nclasses = "
		    "stairs\n[CascadeDetector.stairs]\nupscal = 2\n");
		FAIL();
	}
	catch (const ConfigError& e)
	{
		EXPECT_NE(
		    std::string(e.what()).find("CascadeDetector.stairs"),
		    std::string::npos);
		EXPECT_NE(std::string(e.what()).find("upscal"), std::string::npos);
	}
	EXPECT_THROW(load("[CascadeDetector]\nclasses = sofa\n"), ConfigError);
	EXPECT_THROW(
	    load("[CascadeDetector]\nprojection = fisheye\n"), ConfigError);
	EXPECT_THROW(load("[CascadeDetector]\nthreads = -1\n"), ConfigError);
	EXPECT_EQ(load("[CascadeDetector]\nthreads = 0\n").threads, 0);
	EXPECT_THROW(
	    load(
	        "[CascadeDetector]\nclasses = "
	        "stairs\n[CascadeDetector.stairs]\nmin_top_m = 3\nmax_top_m = 2\n"),
	    ConfigError);
	EXPECT_THROW(
	    load("[CascadeDetector]\nclasses = "
	         "stairs\n[CascadeDetector.stairs]\nwindow_step = 9\n"),
	    ConfigError);
	EXPECT_THROW(
	    load("[CascadeDetector]\nsegment_range_gap_m = -0.1\n"), ConfigError);
	EXPECT_THROW(
	    load("[CascadeDetector]\nsegment_max_taller = -1\n"), ConfigError);
	EXPECT_THROW(
	    load("[CascadeDetector]\nclasses = "
	         "stairs\n[CascadeDetector.stairs]\nsegment_candidates = maybe\n"),
	    ConfigError);
	EXPECT_THROW(
	    load("[CascadeDetector]\nclasses = "
	         "stairs\n[CascadeDetector.stairs]\nmax_continuing_share = 1.5\n"),
	    ConfigError);
	EXPECT_THROW(
	    load("[CascadeDetector]\nclasses = "
	         "stairs\n[CascadeDetector.stairs]\nmin_flat_face_share = -0.1\n"),
	    ConfigError);
	EXPECT_THROW(
	    load("[CascadeDetector]\nclasses = "
	         "stairs\n[CascadeDetector.stairs]\nside_bearing_deg = 95\n"),
	    ConfigError);
	EXPECT_THROW(
	    load("[CascadeDetector]\nclasses = "
	         "stairs\n[CascadeDetector.stairs]\nside_min_shape_score = 2\n"),
	    ConfigError);
	EXPECT_THROW(
	    load("[CascadeDetector]\nclasses = "
	         "stairs\n[CascadeDetector.stairs]\nmin_separation_m = -1\n"),
	    ConfigError);
	EXPECT_THROW(
	    load("[CascadeDetector]\nclasses = "
	         "stairs\n[CascadeDetector.stairs]\ngrow_m = 11\n"),
	    ConfigError);
	// Round trip through save.
	CascadeDetector::TOptions o;
	o.threads = 2;
	o.classes[2].windowStep = 2;
	o.classes[1].segmentCandidates = true;
	o.segmentRangeGap = 0.25;
	o.segmentMaxTaller = 0.5;
	o.classes[1].cascadeSupport = true;
	o.classes[0].maxContinuingShare = 0.25;
	o.classes[2].minSeparation = 1.25;
	o.classes[2].grow = 0.75;
	CascadeDetector::TOptions back = test::savedAndLoaded(o, "CascadeDetector");
	EXPECT_EQ(back.threads, 2);
	ASSERT_EQ(back.classes.size(), o.classes.size());
	EXPECT_EQ(back.rangeScales, o.rangeScales);
	EXPECT_DOUBLE_EQ(back.rangeScaleSlack, o.rangeScaleSlack);
	EXPECT_DOUBLE_EQ(back.rangeCut, o.rangeCut);
	EXPECT_EQ(back.rangeObjectsOnly, o.rangeObjectsOnly);
	EXPECT_DOUBLE_EQ(back.classes[1].farUpscale, o.classes[1].farUpscale);
	EXPECT_EQ(back.classes[2].windowStep, 2);
	EXPECT_EQ(back.classes[0].windowStep, 0);
	EXPECT_TRUE(back.classes[1].segmentCandidates);
	EXPECT_FALSE(back.classes[0].segmentCandidates);
	EXPECT_DOUBLE_EQ(back.segmentRangeGap, 0.25);
	EXPECT_DOUBLE_EQ(back.segmentMaxTaller, 0.5);
	EXPECT_TRUE(back.classes[1].cascadeSupport);
	EXPECT_FALSE(back.classes[2].cascadeSupport);
	EXPECT_DOUBLE_EQ(back.classes[0].maxContinuingShare, 0.25);
	EXPECT_DOUBLE_EQ(back.classes[1].maxContinuingShare, 1);
	EXPECT_DOUBLE_EQ(back.classes[2].minSeparation, 1.25);
	EXPECT_DOUBLE_EQ(back.classes[2].grow, 0.75);
	EXPECT_NEAR(
	    back.classes[0].farMaxElevation, o.classes[0].farMaxElevation, 1e-12);
}

TEST(CascadeDetector, MissingOrCorruptCascadeIsAClearError)
{
	CascadeDetector::TOptions o;
	o.baseDir = "/nonexistent";
	EXPECT_THROW(CascadeDetector{o}, CascadeError);
	const auto dir = std::filesystem::temp_directory_path() / "semnav_det_test";
	std::filesystem::create_directories(dir);
	std::ofstream(dir / "washbasin.xml")
	    << "<?xml version=\"1.0\"?>\n<opencv_storage><cascade>";
	o.baseDir = dir.string();
	o.classes.resize(1);
	try
	{
		CascadeDetector d(o);
		FAIL();
	}
	catch (const CascadeError& e)
	{
		EXPECT_NE(
		    std::string(e.what()).find("washbasin.xml"), std::string::npos);
	}
	std::filesystem::remove_all(dir);
}
