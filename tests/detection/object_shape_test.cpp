/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <semnav/common/Error.h>
#include <semnav/common/Label.h>
#include <semnav/detection/CascadeDetector.h>
#include <semnav/detection/ObjectShape.h>
#include <semnav/detection/ShapeVerifier.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <opencv2/core.hpp>

#include "../common/SavedAndLoaded.h"

using namespace semnav;

namespace
{
/** A fresh directory under the system's temporary one, removed at the end
 * of the scope. */
struct TempDir
{
	explicit TempDir(const std::string& tag)
	    : path(
	          std::filesystem::temp_directory_path() /
	          ("semnav_" + tag + "_" + std::to_string(::getpid())))
	{
		std::filesystem::create_directories(path);
	}
	~TempDir() { std::filesystem::remove_all(path); }
	std::string file(const std::string& name) const
	{
		return (path / name).string();
	}
	std::filesystem::path path;
};

/** Points and normals of a 30 x 30 pixel patch 3 m ahead of the sensor:
 * the front of an upright cylinder (r 0.15 m, 0.4 m high), or of a box with
 * a flat front 0.3 m wide. */
struct ShapePatch
{
	cv::Mat points{30, 30, CV_32FC3, cv::Scalar::all(NAN)};
	cv::Mat normals{30, 30, CV_32FC3, cv::Scalar::all(0)};
	cv::Mat mask{30, 30, CV_8U, cv::Scalar(0)};
	cv::Mat labels{30, 30, CV_8U, cv::Scalar(0)};
	std::vector<cv::Point> object, box;
};

ShapePatch front(bool cylinder)
{
	ShapePatch p;
	constexpr double r = 0.15, h = 0.4, x0 = 3.0;
	for (int row = 0; row < 30; row++)
		for (int col = 0; col < 30; col++)
		{
			p.box.emplace_back(col, row);
			if (col < 5 || col >= 25) continue;  // beside the object
			const double z = h * row / 29.0;
			const double s = (col - 14.5) / 10.0;  // -1 .. 1 across
			cv::Vec3f pt, n;
			if (cylinder)
			{
				const double a = std::asin(s * 0.95);
				pt = cv::Vec3f(
				    float(x0 - r * std::cos(a)), float(r * std::sin(a)),
				    float(z));
				n = cv::Vec3f(float(-std::cos(a)), float(std::sin(a)), 0);
			}
			else
			{
				pt = cv::Vec3f(float(x0 - r), float(r * s), float(z));
				n = cv::Vec3f(-1, 0, 0);
			}
			p.points.at<cv::Vec3f>(row, col) = pt;
			p.normals.at<cv::Vec3f>(row, col) = n;
			p.mask.at<uint8_t>(row, col) = 1;
			p.object.emplace_back(col, row);
		}
	return p;
}

ObjectShape::Features describe(const ShapePatch& p)
{
	return ObjectShape::describe(
	    p.points, p.normals, p.mask, p.labels, p.object, p.box, 0.0);
}

int feature(const char* name)
{
	const auto& n = ObjectShape::names();
	for (int i = 0; i < ObjectShape::kFeatures; i++)
		if (std::string(n[i]) == name) return i;
	ADD_FAILURE() << name;
	return 0;
}

/** Two clusters of descriptors: objects around +1 in every feature, others
 * around -1 (seeded). */
void clusters(cv::Mat& samples, cv::Mat& isObject, int n, uint64_t seed)
{
	cv::RNG rng(seed);
	samples.create(2 * n, ObjectShape::kFeatures, CV_32F);
	isObject.create(2 * n, 1, CV_32S);
	for (int i = 0; i < 2 * n; i++)
	{
		const bool object = i < n;
		isObject.at<int>(i) = object ? 1 : 0;
		for (int k = 0; k < ObjectShape::kFeatures; k++)
			samples.at<float>(i, k) =
			    float((object ? 1 : -1) + rng.gaussian(0.7));
	}
}

ObjectShape::Features row(const cv::Mat& samples, int i)
{
	ObjectShape::Features f;
	for (int k = 0; k < ObjectShape::kFeatures; k++)
		f[std::size_t(k)] = samples.at<float>(i, k);
	return f;
}
}  // namespace

TEST(ObjectShape, SizeAndHeightProfileOfAnUprightObject)
{
	const auto f = describe(front(false));
	EXPECT_NEAR(f[std::size_t(feature("range"))], 2.85, 0.01);
	EXPECT_NEAR(f[std::size_t(feature("bearing"))], 0.0, 0.01);
	EXPECT_NEAR(f[std::size_t(feature("width"))], 0.27, 0.03);
	EXPECT_NEAR(f[std::size_t(feature("depth"))], 0.0, 1e-4);
	EXPECT_NEAR(f[std::size_t(feature("top"))], 0.38, 0.02);
	EXPECT_NEAR(f[std::size_t(feature("bottom"))], 0.02, 0.02);
	// Evenly spread over its height: the five height bins share the points.
	float sum = 0;
	for (int k = feature("height_0_20"); k <= feature("height_80_100"); k++)
	{
		EXPECT_GT(f[std::size_t(k)], 0.12f) << k;
		sum += f[std::size_t(k)];
	}
	EXPECT_NEAR(sum, 1.0, 1e-5);
	EXPECT_NEAR(f[std::size_t(feature("width_lower"))], 1.0, 0.1);
	EXPECT_NEAR(f[std::size_t(feature("facing_side"))], 1.0, 1e-6);
	EXPECT_NEAR(f[std::size_t(feature("facing_up"))], 0.0, 1e-6);
	// Nothing else in its box has a range.
	EXPECT_NEAR(f[std::size_t(feature("box_fill"))], 1.0, 1e-5);
}

TEST(ObjectShape, CylinderTurnsAndBulgesWhereABoxFaceDoesNot)
{
	const auto cyl = describe(front(true));
	const auto box = describe(front(false));
	const auto turn = std::size_t(feature("side_turn"));
	const auto curv = std::size_t(feature("front_curvature"));
	const auto oblique = std::size_t(feature("side_oblique"));
	EXPECT_GT(cyl[turn], 0.1f);
	EXPECT_NEAR(box[turn], 0.0, 1e-6);
	EXPECT_GT(cyl[oblique], 0.4f);
	EXPECT_NEAR(box[oblique], 0.0, 1e-6);
	// The cylinder's front is nearer in the middle: depth grows with lat^2.
	EXPECT_GT(cyl[curv], 0.1f);
	EXPECT_NEAR(box[curv], 0.0, 1e-3);
	// A flat face's normals share one 30 deg bin; the cylinder's spread.
	const auto faces = std::size_t(feature("side_two_faces"));
	EXPECT_NEAR(box[faces], 1.0, 1e-6);
	EXPECT_LT(cyl[faces], 0.6f);
}

TEST(ObjectShape, StepsFaceUpAtManyHeightsATableTopAtOne)
{
	// 30 columns x 30 rows of up-facing points: five steps climbing away
	// from the sensor (0.17 m rise, 0.3 m run), or one table top at 0.75 m.
	for (const bool steps : {true, false})
	{
		ShapePatch p;
		for (int row = 0; row < 30; row++)
			for (int col = 0; col < 30; col++)
			{
				const int step = row / 6;
				const float x = 2.0f + 0.05f * float(row);
				const float z = steps ? 0.17f * float(step + 1) : 0.75f;
				p.points.at<cv::Vec3f>(row, col) =
				    cv::Vec3f(x, 0.03f * float(col - 15), z);
				p.normals.at<cv::Vec3f>(row, col) = cv::Vec3f(0, 0, 1);
				p.mask.at<uint8_t>(row, col) = 1;
				p.object.emplace_back(col, row);
				p.box.emplace_back(col, row);
			}
		const auto f = describe(p);
		EXPECT_NEAR(f[std::size_t(feature("facing_up"))], 1.0, 1e-6);
		if (steps)
		{
			EXPECT_EQ(f[std::size_t(feature("up_levels"))], 5.f);
			EXPECT_GT(f[std::size_t(feature("up_height_spread"))], 0.6f);
			EXPECT_GT(f[std::size_t(feature("up_slope"))], 0.9f);
		}
		else
		{
			EXPECT_EQ(f[std::size_t(feature("up_levels"))], 1.f);
			EXPECT_NEAR(f[std::size_t(feature("up_height_spread"))], 0, 1e-6);
		}
		// The height x depth grid: the steps' points climb with depth (the
		// mean depth cell of each occupied height row grows), the table's
		// lie in the top row; they face up wherever there are points.
		constexpr int g = ObjectShape::kGridSide;
		const auto cell = [&](const char* grid, int r, int c)
		{
			return f[std::size_t(
			    feature((std::string(grid) + "_" + std::to_string(r) + "_" +
			             std::to_string(c))
			                .c_str()))];
		};
		double lastDepth = -1, all = 0, topRow = 0;
		int rows = 0;
		for (int r = 0; r < g; r++)
		{
			double share = 0, depth = 0;
			for (int c = 0; c < g; c++)
			{
				share += cell("share_hd", r, c);
				depth += c * cell("share_hd", r, c);
				EXPECT_NEAR(
				    cell("up_hd", r, c), cell("share_hd", r, c) > 0 ? 1 : -1,
				    1e-6);
			}
			all += share;
			if (r == g - 1) topRow = share;
			if (share == 0) continue;
			rows++;
			EXPECT_GT(depth / share, lastDepth) << "row " << r;
			lastDepth = depth / share;
		}
		EXPECT_NEAR(all, 1.0, 1e-5);
		if (steps)
			EXPECT_EQ(rows, 5);
		else
			EXPECT_NEAR(topRow, 1.0, 1e-5);
	}
}

TEST(ObjectShape, WallsAroundAndNoPoints)
{
	ShapePatch p = front(false);
	// The columns beside the object are a wall behind it.
	for (int row = 0; row < 30; row++)
		for (int col : {0, 1, 2, 3, 4, 25, 26, 27, 28, 29})
		{
			p.points.at<cv::Vec3f>(row, col) = cv::Vec3f(3.2f, 0, 0.5f);
			p.labels.at<uint8_t>(row, col) = uint8_t(Label::Wall);
		}
	const auto f = describe(p);
	EXPECT_NEAR(f[std::size_t(feature("wall_around"))], 10.0 / 30.0, 1e-5);
	EXPECT_NEAR(f[std::size_t(feature("box_fill"))], 20.0 / 30.0, 1e-5);
	p.object = {{0, 0}};  // a wall point alone is still described
	p.points.at<cv::Vec3f>(0, 0) = cv::Vec3f(NAN, NAN, NAN);
	const auto none = describe(p);
	EXPECT_TRUE(std::all_of(
	    none.begin(), none.end(), [](float v) { return v == 0.f; }));
}

TEST(ShapeVerifier, SeparatesAndRoundTrips)
{
	cv::Mat samples, isObject, test, testIsObject;
	clusters(samples, isObject, 150, 1);
	clusters(test, testIsObject, 50, 2);
	ShapeVerifier::TrainParams tp;
	tp.trees = 30;
	const auto v = ShapeVerifier::train(samples, isObject, tp);
	int right = 0;
	for (int i = 0; i < test.rows; i++)
		right +=
		    (v.score(row(test, i)) >= 0.5) == (testIsObject.at<int>(i) == 1);
	EXPECT_GE(right, 95);
	const TempDir dir("shape");
	const auto path = dir.file("s.xml");
	v.save(path);
	const auto back = ShapeVerifier::load(path);
	for (int i = 0; i < test.rows; i++)
		EXPECT_DOUBLE_EQ(back.score(row(test, i)), v.score(row(test, i)));
	// Same samples and seed, same forest.
	ShapeVerifier::train(samples, isObject, tp).save(path + "2");
	std::ifstream a(path), b(path + "2");
	const std::string sa((std::istreambuf_iterator<char>(a)), {}),
	    sb((std::istreambuf_iterator<char>(b)), {});
	EXPECT_EQ(sa, sb);
}

TEST(ShapeVerifier, WithoutGridsOnlyTheScalarFeaturesCount)
{
	cv::Mat samples, isObject;
	clusters(samples, isObject, 150, 1);
	ShapeVerifier::TrainParams tp;
	tp.trees = 20;
	const auto v = ShapeVerifier::train(
	    samples.colRange(0, ObjectShape::kBaseFeatures).clone(), isObject, tp);
	EXPECT_EQ(v.featureCount(), ObjectShape::kBaseFeatures);
	EXPECT_EQ(
	    ShapeVerifier::train(samples, isObject, tp).featureCount(),
	    ObjectShape::kFeatures);
	const TempDir dir("shape_base");
	v.save(dir.file("s.xml.gz"));
	const auto back = ShapeVerifier::load(dir.file("s.xml.gz"));
	EXPECT_EQ(back.featureCount(), ObjectShape::kBaseFeatures);
	// The grids do not move its score.
	for (int i = 0; i < samples.rows; i += 7)
	{
		auto f = row(samples, i);
		const double s = back.score(f);
		EXPECT_EQ(s, back.scoreByOpenCv(f));
		std::fill(f.begin() + ObjectShape::kBaseFeatures, f.end(), 99.f);
		EXPECT_EQ(back.score(f), s);
	}
}

TEST(ObjectShape, RisersClimbAlongTheColumnsABoxFrontDoesNot)
{
	// Each column from the sensor: five risers 0.17 m high, each 0.3 m
	// farther than the one below (treads not seen, as far away), or a box's
	// flat front.
	ShapePatch flight;
	for (int row = 0; row < 30; row++)
		for (int col = 0; col < 30; col++)
		{
			const int step = row / 6;
			flight.points.at<cv::Vec3f>(row, col) = cv::Vec3f(
			    6.0f + 0.3f * float(step), 0.04f * float(col - 15),
			    0.17f * float(step) + 0.17f * float(row % 6) / 6.0f);
			flight.normals.at<cv::Vec3f>(row, col) = cv::Vec3f(-1, 0, 0);
			flight.mask.at<uint8_t>(row, col) = 1;
			flight.object.emplace_back(col, row);
			flight.box.emplace_back(col, row);
		}
	const auto f = describe(flight);
	EXPECT_NEAR(f[std::size_t(feature("steps_per_column"))], 4, 1e-6);
	EXPECT_NEAR(f[std::size_t(feature("climbing_columns"))], 1, 1e-6);
	EXPECT_NEAR(f[std::size_t(feature("step_run"))], 0.3, 2e-3);
	EXPECT_NEAR(f[std::size_t(feature("step_rise"))], 0.17, 2e-3);
	// Not described for a forest that does not read them.
	const auto without = ObjectShape::describe(
	    flight.points, flight.normals, flight.mask, flight.labels,
	    flight.object, flight.box, 0.0, false);
	EXPECT_EQ(without[std::size_t(feature("steps_per_column"))], 0.f);
	const auto box = describe(front(false));
	for (const char* name :
	     {"steps_per_column", "climbing_columns", "step_run", "step_rise"})
		EXPECT_EQ(box[std::size_t(feature(name))], 0.f) << name;
}

TEST(ShapeVerifier, ForestWithStepsReadsThemWhereTheyAre)
{
	// Objects and others differ only in the steps: a forest over the
	// scalar features and the steps (after the grids in the descriptor)
	// tells them apart, and the grids do not move its score.
	cv::RNG rng(3);
	const std::vector<int> columns =
	    ObjectShape::columnsOf(ObjectShape::featureCount(false, true));
	ASSERT_EQ(columns.size(), std::size_t(ObjectShape::kBaseFeatures + 4));
	EXPECT_EQ(columns.back(), ObjectShape::kFeatures - 1);
	EXPECT_TRUE(ObjectShape::columnsOf(ObjectShape::kBaseFeatures + 1).empty());
	constexpr int n = 200;
	std::vector<ObjectShape::Features> all(2 * n);
	cv::Mat samples(2 * n, int(columns.size()), CV_32F);
	cv::Mat isObject(2 * n, 1, CV_32S);
	for (int i = 0; i < 2 * n; i++)
	{
		const bool object = i < n;
		for (auto& v : all[std::size_t(i)]) v = float(rng.gaussian(1.0));
		for (int k = ObjectShape::kStepsAt; k < ObjectShape::kFeatures; k++)
			all[std::size_t(i)][std::size_t(k)] += object ? 2.f : -2.f;
		isObject.at<int>(i) = object;
		for (std::size_t c = 0; c < columns.size(); c++)
			samples.at<float>(i, int(c)) =
			    all[std::size_t(i)][std::size_t(columns[c])];
	}
	ShapeVerifier::TrainParams tp;
	tp.trees = 20;
	const TempDir dir("shape_steps");
	ShapeVerifier::train(samples, isObject, tp).save(dir.file("s.xml.gz"));
	const auto v = ShapeVerifier::load(dir.file("s.xml.gz"));
	EXPECT_EQ(v.featureCount(), int(columns.size()));
	EXPECT_TRUE(v.readsSteps());
	EXPECT_FALSE(ShapeVerifier::train(
	                 samples.colRange(0, ObjectShape::kBaseFeatures).clone(),
	                 isObject, tp)
	                 .readsSteps());
	int right = 0;
	for (int i = 0; i < 2 * n; i++)
	{
		auto f = all[std::size_t(i)];
		const double s = v.score(f);
		EXPECT_EQ(s, v.scoreByOpenCv(f));
		right += (s > 0.5) == (i < n);
		std::fill(
		    f.begin() + ObjectShape::kBaseFeatures,
		    f.begin() + ObjectShape::kStepsAt, 99.f);
		EXPECT_EQ(v.score(f), s);
	}
	EXPECT_GT(right, 2 * n * 95 / 100);
}

TEST(ShapeVerifier, FlatTreesVoteAsOpenCv)
{
	// The shipped forests and a small trained one, on features drawn around
	// the values candidates have (and on exact zeros, a common value): the
	// flat trees' score is RTrees::getVotes', to the last bit.
	std::vector<ShapeVerifier> models;
	for (const char* l : {"washbasin", "wastebasket", "stairs"})
		models.push_back(ShapeVerifier::load(
		    std::string(SEMNAV_SOURCE_DIR) + "/datasets/cascades/" + l +
		    "-shape.xml.gz"));
	cv::Mat samples, isObject;
	clusters(samples, isObject, 150, 1);
	ShapeVerifier::TrainParams tp;
	tp.trees = 30;
	models.push_back(ShapeVerifier::train(samples, isObject, tp));
	cv::RNG rng(7);
	std::size_t between = 0;
	for (const auto& m : models)
		for (int i = 0; i < 2000; i++)
		{
			ObjectShape::Features f{};
			for (auto& v : f)
				v = rng.uniform(0, 4) == 0
				        ? 0.f
				        : float(rng.uniform(-0.5, 8.0) * rng.uniform(0.0, 1.0));
			const double a = m.score(f), b = m.scoreByOpenCv(f);
			EXPECT_EQ(a, b) << "sample " << i;
			between += a > 0 && a < 1;
		}
	EXPECT_GT(between, 1000u) << "the samples split the trees' votes";
}

TEST(ShapeVerifier, BadModelsAndSamplesAreClearErrors)
{
	const TempDir dir("shape_bad");
	const auto path = dir.file("bad.xml");
	std::ofstream(path) << "<?xml version=\"1.0\"?>\n<opencv_storage><x>";
	for (const auto& p : {path, dir.file("missing.xml")}) try
		{
			ShapeVerifier::load(p);
			FAIL() << p;
		}
		catch (const IoError& e)
		{
			EXPECT_NE(std::string(e.what()).find(p), std::string::npos);
		}
	// A forest over other features is not a shape model.
	{
		cv::FileStorage fs(path, cv::FileStorage::WRITE);
		auto f = cv::ml::RTrees::create();
		f->setMaxDepth(2);
		f->setTermCriteria({cv::TermCriteria::MAX_ITER, 2, 0});
		cv::Mat s = (cv::Mat_<float>(4, 2) << 0, 0, 0, 1, 1, 0, 1, 1);
		cv::Mat r = (cv::Mat_<int>(4, 1) << 0, 0, 1, 1);
		f->train(s, cv::ml::ROW_SAMPLE, r);
		fs << f->getDefaultName() << "{";
		f->write(fs);
		fs << "}";
	}
	EXPECT_THROW(ShapeVerifier::load(path), IoError);
	cv::Mat wrongWidth(
	    4, ObjectShape::kBaseFeatures + 1, CV_32F, cv::Scalar(0));
	EXPECT_THROW(
	    ShapeVerifier::train(
	        wrongWidth, cv::Mat(4, 1, CV_32S, cv::Scalar(0)), {}),
	    Error);
	cv::Mat samples, isObject;
	clusters(samples, isObject, 10, 1);
	isObject.setTo(1);
	EXPECT_THROW(ShapeVerifier::train(samples, isObject, {}), Error);
}

TEST(ShapeVerifier, DetectorOptionsLoadSaveAndCheck)
{
	mrpt::config::CConfigFileMemory c(
	    "[CascadeDetector]\nclasses = stairs\nrange_scales = true\n"
	    "[CascadeDetector.stairs]\nshape_model = s.xml\nmin_shape_score = "
	    "0.7\nmax_stages = 12\n");
	CascadeDetector::TOptions o;
	o.loadFromConfigFile(c, "CascadeDetector");
	EXPECT_EQ(o.classes[0].shapeModel, "s.xml");
	EXPECT_DOUBLE_EQ(o.classes[0].minShapeScore, 0.7);
	EXPECT_EQ(o.classes[0].maxStages, 12);
	const auto back = test::savedAndLoaded(o, "CascadeDetector");
	EXPECT_EQ(back.classes[0].shapeModel, "s.xml");
	EXPECT_DOUBLE_EQ(back.classes[0].minShapeScore, 0.7);
	EXPECT_EQ(back.classes[0].maxStages, 12);
	mrpt::config::CConfigFileMemory bad(
	    "[CascadeDetector]\nclasses = stairs\n"
	    "[CascadeDetector.stairs]\nmin_shape_score = 1.5\n");
	EXPECT_THROW(o.loadFromConfigFile(bad, "CascadeDetector"), ConfigError);
}
