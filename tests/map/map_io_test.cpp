/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <octomap/OcTree.h>
#include <semnav/common/Error.h>
#include <semnav/map/MapIO.h>
#include <yaml-cpp/yaml.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <opencv2/imgcodecs.hpp>
#include <set>
#include <thread>

#include "MapTestUtils.h"

using namespace semnav;
using semnav::test::floorFan;
using semnav::test::makeFakeSweep;
namespace fs = std::filesystem;

namespace
{
fs::path tempDir(const std::string& name)
{
	const fs::path d = fs::temp_directory_path() /
	                   ("semnav_" + name + "_" + std::to_string(::getpid()));
	fs::remove_all(d);
	return d;
}

/** A small map: floor, a box, a ceiling point, a wastebasket detection. */
void buildMap(SemanticMap& m)
{
	auto pts = floorFan(3.0);
	for (double y = -0.3; y <= 0.3; y += 0.02)
		pts.push_back({2.5, y, 0.3, Label::Obstacle});
	pts.push_back({1.0, 0.0, 2.5, Label::Ceiling});
	auto f = makeFakeSweep(pts);
	Detection d;
	d.label = Label::Wastebasket;
	d.imageBox = cv::Rect(0, 0, 3, 1);
	d.centroid = {1.5, 0.8, 0.2};
	d.extent = {0.3, 0.3, 0.4};
	d.shapeScore = 0.75;
	f.labeled.detections = {d};
	m.insert(f.sweep, f.labeled, mrpt::poses::CPose2D(1, 1, 0.3));
	m.insert(f.sweep, f.labeled, mrpt::poses::CPose2D(1.2, 1, 0.35));
}

/** What ROS map_server does with map.yaml and its image (trinary mode). */
struct MapServerMap
{
	double resolution, originX, originY;
	int width, height;
	std::vector<int8_t>
	    data;  // row-major from the bottom row: 100 occ, 0 free, -1 unknown
};
MapServerMap loadLikeMapServer(const fs::path& yamlPath)
{
	const YAML::Node y = YAML::LoadFile(yamlPath.string());
	MapServerMap m;
	m.resolution = y["resolution"].as<double>();
	m.originX = y["origin"][0].as<double>();
	m.originY = y["origin"][1].as<double>();
	const double occ = y["occupied_thresh"].as<double>(),
	             free = y["free_thresh"].as<double>();
	const bool negate = y["negate"].as<int>() != 0;
	const cv::Mat img = cv::imread(
	    (yamlPath.parent_path() / y["image"].as<std::string>()).string(),
	    cv::IMREAD_GRAYSCALE);
	m.width = img.cols;
	m.height = img.rows;
	for (int j = 0; j < img.rows; j++)
		for (int i = 0; i < img.cols; i++)
		{
			const int v = img.at<uint8_t>(img.rows - 1 - j, i);
			const double p = negate ? v / 255.0 : (255.0 - v) / 255.0;
			m.data.push_back(p > occ ? 100 : p < free ? 0 : -1);
		}
	return m;
}
}  // namespace

TEST(MapIO, SaveThenLoadGivesTheSameMap)
{
	SemanticMap a;
	buildMap(a);
	const auto dir = tempDir("mapio_rt");
	MapIO::save(a, dir.string());
	for (const char* f :
	     {"map.yaml", "occupancy.png", "labels.png", "cost.png", "objects.png",
	      "map.png", "octomap.bt"})
		EXPECT_TRUE(fs::exists(dir / f)) << f;

	SemanticMap b;
	MapIO::load(dir.string(), b);
	EXPECT_EQ(b.geometry(), a.geometry());
	EXPECT_EQ(b.layers(), a.layers());
	for (const auto& name : a.layers())
	{
		const auto &la = a.get(name), &lb = b.get(name);
		ASSERT_EQ(la.size(), lb.size());
		for (std::size_t i = 0; i < la.size(); i++)
			ASSERT_TRUE(
			    la[i] == lb[i] || (std::isnan(la[i]) && std::isnan(lb[i])))
			    << name << " cell " << i;
	}
	EXPECT_EQ(b.occupancyGrid().getRawMap(), a.occupancyGrid().getRawMap());
	ASSERT_EQ(b.allInstances().size(), a.allInstances().size());
	const auto &oa = a.allInstances()[0], &ob = b.allInstances()[0];
	EXPECT_EQ(ob.id, oa.id);
	EXPECT_EQ(ob.label, Label::Wastebasket);
	EXPECT_EQ(ob.observations, 2u);
	EXPECT_DOUBLE_EQ(ob.bestShapeScore, 0.75);
	EXPECT_EQ(b.reported(ob), a.reported(oa));
	EXPECT_NEAR(ob.centroid.x, oa.centroid.x, 1e-9);
	EXPECT_NEAR(ob.maxCorner.y, oa.maxCorner.y, 1e-9);
	EXPECT_EQ(b.sweepsInserted(), 2u);
	EXPECT_EQ(b.octree().size(), a.octree().size());
	fs::remove_all(dir);
}

TEST(MapIO, MapYamlReadsLikeMapServer)
{
	SemanticMap a;
	buildMap(a);
	const auto dir = tempDir("mapio_ms");
	MapIO::save(a, dir.string());
	const auto ms = loadLikeMapServer(dir / "map.yaml");
	const auto& g = a.geometry();
	ASSERT_EQ(ms.width, g.cols);
	ASSERT_EQ(ms.height, g.rows);
	EXPECT_DOUBLE_EQ(ms.resolution, g.resolution);
	std::size_t occ = 0, free = 0;
	for (int cy = 0; cy < g.rows; cy++)
		for (int cx = 0; cx < g.cols; cx++)
		{
			const int8_t v =
			    ms.data[static_cast<std::size_t>(cy) * g.cols + cx];
			switch (a.cellState(cx, cy))
			{
				case SemanticMap::CellState::Occupied:
					ASSERT_EQ(v, 100);
					occ++;
					break;
				case SemanticMap::CellState::Free:
					ASSERT_EQ(v, 0);
					free++;
					break;
				default:
					ASSERT_EQ(v, -1);
			}
		}
	EXPECT_GT(occ, 5u);
	EXPECT_GT(free, 500u);
	// A world point maps to the same cell both ways.
	int cx, cy;
	ASSERT_TRUE(a.worldToCell(2.01, 1.51, cx, cy));
	EXPECT_EQ(
	    static_cast<int>(std::floor((2.01 - ms.originX) / ms.resolution)), cx);
	EXPECT_EQ(
	    static_cast<int>(std::floor((1.51 - ms.originY) / ms.resolution)), cy);
	fs::remove_all(dir);
}

TEST(MapIO, CorruptOrMissingFilesGiveClearErrors)
{
	SemanticMap a;
	buildMap(a);
	const auto dir = tempDir("mapio_bad");
	auto expectError = [&](const std::string& needle)
	{
		SemanticMap b;
		try
		{
			MapIO::load(dir.string(), b);
			FAIL() << "loaded a broken map (" << needle << ")";
		}
		catch (const IoError& e)
		{
			EXPECT_NE(std::string(e.what()).find(needle), std::string::npos)
			    << e.what();
		}
	};
	MapIO::save(a, dir.string());
	fs::remove(dir / "labels.png");
	expectError("labels.png");

	MapIO::save(a, dir.string());
	std::ofstream(dir / "layers" / "cost.pfm") << "garbage";
	expectError("cost.pfm");

	MapIO::save(a, dir.string());
	cv::imwrite(
	    (dir / "occupancy.png").string(),
	    cv::Mat(3, 3, CV_8UC1, cv::Scalar(0)));
	expectError("occupancy.png");

	MapIO::save(a, dir.string());
	std::ofstream(dir / "map.yaml")
	    << "image: occupancy.png\nresolution: [oops\n";
	expectError("map.yaml:");

	MapIO::save(a, dir.string());
	{
		std::ifstream in(dir / "map.yaml");
		std::stringstream ss;
		ss << in.rdbuf();
		std::string t = ss.str();
		t.replace(t.find("label: wastebasket"), 18, "label: trashcan");
		std::ofstream(dir / "map.yaml") << t;
	}
	expectError("trashcan");
	EXPECT_THROW(MapIO::load((dir / "nothing").string(), a), IoError);
	fs::remove_all(dir);
}

namespace
{
/** map.yaml of `dir` with its first `from` replaced by `to`. */
void editMapYaml(
    const fs::path& dir, const std::string& from, const std::string& to)
{
	std::ifstream in(dir / "map.yaml");
	std::stringstream ss;
	ss << in.rdbuf();
	std::string t = ss.str();
	const auto at = t.find(from);
	ASSERT_NE(at, std::string::npos) << from;
	t.replace(at, from.size(), to);
	std::ofstream(dir / "map.yaml") << t;
}

/** The message of the IoError that loading `dir` throws ("" if none). */
std::string loadError(const fs::path& dir)
{
	try
	{
		SemanticMap m;
		MapIO::load(dir.string(), m);
	}
	catch (const IoError& e)
	{
		return e.what();
	}
	return "";
}
}  // namespace

TEST(MapIO, BadGeometryNamesItsKey)
{
	SemanticMap a;
	buildMap(a);
	const auto dir = tempDir("mapio_geometry");
	MapIO::save(a, dir.string());
	editMapYaml(dir, "resolution: 0.05", "resolution: -0.05");
	std::string e = loadError(dir);
	EXPECT_NE(
	    e.find("map.yaml:2: resolution: must be a positive"), std::string::npos)
	    << e;
	MapIO::save(a, dir.string());
	editMapYaml(dir, "size: [", "size: [99999999, 9]\n  was: [");
	e = loadError(dir);
	EXPECT_NE(e.find("semnav.size: "), std::string::npos) << e;
	EXPECT_NE(e.find("no map size"), std::string::npos) << e;
	fs::remove_all(dir);
}

TEST(MapIO, CorruptImageHeadersAreOneLineNamingTheFile)
{
	SemanticMap a;
	buildMap(a);
	const auto dir = tempDir("mapio_headers");
	const auto bytesOf = [](const fs::path& p)
	{
		std::ifstream in(p, std::ios::binary);
		return std::string(std::istreambuf_iterator<char>(in), {});
	};
	struct Case
	{
		std::string file, needle;
		std::function<std::string(std::string)> corrupt;
	};
	const Case cases[] = {
	    {"layers/cost.pfm", "map.yaml says",
	     [](std::string) { return "Pf\n99999999 99999999\n-1\n\0\0\0\0"; }},
	    {"layers/cost.pfm", "bad header",
	     [](std::string) { return "Pf\n12 abc\n-1\n"; }},
	    {"layers/roughness.pfm", "bytes of pixels",
	     [](std::string b) { return b.substr(0, b.size() / 2); }},
	    {"labels.png", "cannot decode",
	     [](std::string b)
	     {
		     for (std::size_t i = 60; i < b.size() - 20; i++) b[i] ^= 0x55;
		     return b;
	     }},
	    {"occupancy.png", "map.yaml says",
	     [](std::string b)
	     {
		     b[16] = '\x7f';  // IHDR width: 2^31 - ...
		     return b;
	     }},
	};
	for (const auto& c : cases)
	{
		MapIO::save(a, dir.string());
		const std::string bytes = c.corrupt(bytesOf(dir / c.file));
		std::ofstream(dir / c.file, std::ios::binary) << bytes;
		testing::internal::CaptureStderr();
		const std::string e = loadError(dir);
		const std::string printed = testing::internal::GetCapturedStderr();
		EXPECT_NE(e.find((dir / c.file).string()), std::string::npos) << e;
		EXPECT_NE(e.find(c.needle), std::string::npos) << e;
		EXPECT_EQ(printed, "") << c.file << ": OpenCV or libpng printed";
	}
	fs::remove_all(dir);
}

TEST(MapIO, NonFiniteOrNegativeLayerValuesNameTheFileAndPixel)
{
	SemanticMap a;
	buildMap(a);
	const auto dir = tempDir("mapio_values");
	const float nan = std::numeric_limits<float>::quiet_NaN(),
	            inf = std::numeric_limits<float>::infinity();
	struct Case
	{
		std::string layer;
		float value;
		std::string shown;
	};
	const Case cases[] = {
	    {"cost", nan, "nan"},
	    {"labels", -3.0f, "-3"},
	    {"observations", inf, "inf"},
	    {"roughness", -inf, "-inf"},
	    {"occupancy_logodds", 1e6f, "1e+06"},
	};
	for (const auto& c : cases)
	{
		MapIO::save(a, dir.string());
		const fs::path pfm = dir / "layers" / (c.layer + ".pfm");
		cv::Mat img = cv::imread(pfm.string(), cv::IMREAD_UNCHANGED);
		ASSERT_EQ(img.type(), CV_32FC1);
		img.at<float>(2, 5) = c.value;
		cv::imwrite(pfm.string(), img);
		const std::string e = loadError(dir);
		EXPECT_NE(
		    e.find(pfm.string() + ": pixel (5, 2) is " + c.shown),
		    std::string::npos)
		    << e;
	}
	// NaN is roughness's "no data"; the saved maps hold it.
	MapIO::save(a, dir.string());
	EXPECT_EQ(loadError(dir), "");
	// Roughness is a mean dot product of normals, in [-1, 1]: negative
	// values load (semnav-robot's office map had -0.166), 1.5 does not.
	{
		const fs::path pfm = dir / "layers" / "roughness.pfm";
		cv::Mat img = cv::imread(pfm.string(), cv::IMREAD_UNCHANGED);
		img.at<float>(2, 5) = -0.17f;
		cv::imwrite(pfm.string(), img);
		EXPECT_EQ(loadError(dir), "");
		img.at<float>(2, 5) = 1.5f;
		cv::imwrite(pfm.string(), img);
		EXPECT_NE(
		    loadError(dir).find("roughness.pfm: pixel (5, 2) is 1.5; values "
		                        "must be NaN (no data) or finite and >= "
		                        "-1.001 and <= 1.001"),
		    std::string::npos)
		    << loadError(dir);
	}
	fs::remove_all(dir);
}

TEST(MapIO, OnlyReportedObjectsAreSaved)
{
	SemanticMap a;
	buildMap(a);
	// A 4 cm "door" (a wall fragment): below door_min_height_m.
	const int tiny =
	    a.addInstance(Label::Door, {1.5, 1.0, 0.4}, {1.6, 1.1, 0.44});
	ASSERT_FALSE(a.reported(a.instance(tiny)));
	const int door =
	    a.addInstance(Label::Door, {2.0, 1.0, 0.0}, {2.1, 1.6, 2.0});
	ASSERT_TRUE(a.reported(a.instance(door)));
	const auto dir = tempDir("mapio_reported");
	MapIO::save(a, dir.string());

	const YAML::Node objects =
	    YAML::LoadFile((dir / "map.yaml").string())["semnav"]["objects"];
	std::set<int> saved;
	for (const auto& o : objects) saved.insert(o["id"].as<int>());
	std::set<int> reported;
	for (const auto& o : a.instances()) reported.insert(o.id);
	EXPECT_EQ(saved, reported);
	EXPECT_EQ(saved.count(tiny), 0u);
	EXPECT_EQ(saved.count(door), 1u);
	const cv::Mat ids =
	    cv::imread((dir / "objects.png").string(), cv::IMREAD_UNCHANGED);
	EXPECT_EQ(cv::countNonZero(ids == tiny), 0)
	    << "objects.png keeps the candidate";
	EXPECT_GT(cv::countNonZero(ids == door), 0);

	SemanticMap b;
	MapIO::load(dir.string(), b);
	EXPECT_EQ(b.allInstances().size(), reported.size());
	EXPECT_THROW(b.instance(tiny), Error);
	for (const float id : b.get("objects"))
		ASSERT_NE(static_cast<int>(id), tiny);
	fs::remove_all(dir);
}

TEST(MapIO, ConcurrentLoadsSeeOneWholeMapWhileSavesReplaceIt)
{
	// Two maps that differ in every file: one and two sweeps.
	SemanticMap a, b;
	buildMap(b);
	{
		const auto f = makeFakeSweep(floorFan(2.0));
		a.insert(f.sweep, f.labeled, mrpt::poses::CPose2D(1, 1, 0.3));
	}
	const auto dir = tempDir("mapio_concurrent");
	MapIO::save(a, dir.string());
	std::atomic<bool> stop{false};
	std::thread writer(
	    [&]
	    {
		    for (int i = 0; !stop; i++)
			    MapIO::save(i % 2 ? a : b, dir.string());
	    });
	int loads = 0, sawA = 0, sawB = 0;
	for (; loads < 40; loads++)
	{
		SemanticMap m;
		ASSERT_NO_THROW(MapIO::load(dir.string(), m)) << "load " << loads;
		const SemanticMap& expected = m.sweepsInserted() == 1 ? a : b;
		(m.sweepsInserted() == 1 ? sawA : sawB)++;
		// Every layer from the save that wrote map.yaml.
		for (const auto& name : expected.layers())
		{
			const auto &x = expected.get(name), &y = m.get(name);
			ASSERT_EQ(x.size(), y.size()) << name;
			for (std::size_t i = 0; i < x.size(); i++)
				ASSERT_TRUE(
				    x[i] == y[i] || (std::isnan(x[i]) && std::isnan(y[i])))
				    << "load " << loads << ": " << name << " cell " << i
				    << " is from the other map";
		}
		ASSERT_EQ(m.octree().size(), expected.octree().size());
	}
	stop = true;
	writer.join();
	EXPECT_GT(sawA + sawB, 0);
	fs::remove_all(dir);
}

TEST(MapIO, RefusesForeignDirectoriesAndNamesAnInterruptedSave)
{
	SemanticMap a;
	buildMap(a);
	const auto root = tempDir("mapio_foreign");
	fs::create_directories(root / "out");
	std::ofstream(root / "out" / "notes.txt") << "mine";
	EXPECT_THROW(MapIO::checkTarget((root / "out").string()), IoError);
	EXPECT_THROW(MapIO::save(a, (root / "out").string()), IoError);
	EXPECT_TRUE(fs::exists(root / "out" / "notes.txt"));

	// A save interrupted between the two renames of the fallback swap.
	MapIO::save(a, (root / "map").string());
	const fs::path ready = root / ".map.ready-999999999";
	fs::rename(root / "map", ready);
	try
	{
		SemanticMap b;
		MapIO::load((root / "map").string(), b);
		FAIL() << "loaded a missing map";
	}
	catch (const IoError& e)
	{
		const std::string m = e.what();
		EXPECT_NE(m.find("interrupted"), std::string::npos) << m;
		EXPECT_NE(m.find(ready.string()), std::string::npos) << m;
	}
	// The next save recovers it first, then replaces it.
	MapIO::save(a, (root / "map").string());
	SemanticMap c;
	MapIO::load((root / "map").string(), c);
	EXPECT_EQ(c.sweepsInserted(), a.sweepsInserted());
	EXPECT_FALSE(fs::exists(ready));
	fs::remove_all(root);
}
