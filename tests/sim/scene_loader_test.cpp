/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <semnav/common/ClassRegistry.h>
#include <semnav/common/Error.h>
#include <semnav/sim/SceneLoader.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

using namespace semnav;

namespace
{
constexpr double kDeg = M_PI / 180;

/** A complete scene using every key of the format. */
const char* kFullScene = R"(# every key
name: full
bounds: [-1, -2, 11, 8]
ceiling_height: 2.5
objects:
  - {label: wall, box: {center: [5, 0.05, 1.25], size: [10, 0.1, 2.5], yaw: 30}}
  - {label: door, box: {center: [3, 7.9, 1.0], size: [0.9, 0.04, 2.0]}}
  - {label: wastebasket, cylinder: {center: [1.5, 1.0, 0.2], radius: 0.15, height: 0.4}}
  - label: washbasin
    parts:
      - {box: {center: [10, 0.3, 0.8], size: [0.5, 0.4, 0.15], yaw: -90}}
      - cylinder:
          center: [10, 0.25, 0.4]
          radius: 0.08
          height: 0.8
  - {label: stairs, stairs: {origin: [8, 4], yaw: 90, steps: 5, rise: 0.17, run: 0.28, width: 1.2}}
  - {label: grass, terrain: {polygon: [[0, 0], [5, 0], [5, 3], [0, 3]], roughness: 0.03}}
sensor:
  mount: [0.1, -0.05, 0.5]
  phi: [-60, 60, 1]
  theta: [-10, 80, 0.25]
  max_range: 6.5
  range_noise: 0.01
odometry: {trans_noise: 0.03, rot_noise_deg_per_m: 1.5, rot_bias_deg_per_m: -3.5}
trajectory:
  - [1.0, 4.0, 0]
  - [3.0, 4.5, 90]
  - [3.5, 6.0, -45]
)";

/** Minimal valid scene; error tests edit it line by line:
 * 1 name, 2 bounds, 3 objects, 4 the wall, 5 trajectory, 6 a pose. */
const std::vector<std::string> kBaseLines = {
    "name: t",
    "bounds: [0, 0, 10, 10]",
    "objects:",
    "  - {label: wall, box: {center: [1, 1, 1], size: [1, 1, 2]}}",
    "trajectory:",
    "  - [1, 2, 0]"};

/** Base scene with line `lineNo` (1-based) replaced by `text` (several
 * lines allowed); lineNo 0 replaces nothing. */
std::string edited(std::size_t lineNo, const std::string& text)
{
	std::string s;
	for (std::size_t i = 0; i < kBaseLines.size(); i++)
		s += (i + 1 == lineNo ? text : kBaseLines[i]) + "\n";
	return s;
}

/** The first `n` lines of the base scene. */
std::string firstLines(std::size_t n)
{
	std::string s;
	for (std::size_t i = 0; i < n; i++) s += kBaseLines[i] + "\n";
	return s;
}

std::string appended(const std::string& text)
{
	return edited(0, "") + text + "\n";
}

/** The SceneError message of parsing `yaml`, or "(no error)". */
std::string errorOf(const std::string& yaml)
{
	try
	{
		SceneLoader::parse(yaml, "t.yaml");
	}
	catch (const SceneError& e)
	{
		return e.what();
	}
	return "(no error)";
}

/** Expects an error whose message starts with `t.yaml:<line>: <path>: ` and
 * contains `fragment`, on one line. */
void expectError(
    const std::string& yaml, int line, const std::string& path,
    const std::string& fragment)
{
	const std::string msg = errorOf(yaml);
	const std::string prefix = "t.yaml:" + std::to_string(line) + ": " +
	                           (path.empty() ? "" : path + ": ");
	EXPECT_EQ(msg.rfind(prefix, 0), 0u)
	    << "expected prefix '" << prefix << "' in: " << msg;
	EXPECT_NE(msg.find(fragment), std::string::npos)
	    << "expected '" << fragment << "' in: " << msg;
	EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
}

template <typename T>
const T& partAs(const Scene& s, std::size_t obj, std::size_t part = 0)
{
	return std::get<T>(s.objects.at(obj).parts.at(part));
}
}  // namespace

TEST(SceneLoader, BaseSceneIsValid)
{
	EXPECT_EQ(errorOf(edited(0, "")), "(no error)");
}

TEST(SceneLoader, FullSceneEveryField)
{
	const Scene s = SceneLoader::parse(kFullScene, "full.yaml");
	EXPECT_EQ(s.name, "full");
	EXPECT_DOUBLE_EQ(s.bounds.xmin, -1);
	EXPECT_DOUBLE_EQ(s.bounds.ymin, -2);
	EXPECT_DOUBLE_EQ(s.bounds.xmax, 11);
	EXPECT_DOUBLE_EQ(s.bounds.ymax, 8);
	ASSERT_TRUE(s.ceilingHeight.has_value());
	EXPECT_DOUBLE_EQ(*s.ceilingHeight, 2.5);

	ASSERT_EQ(s.objects.size(), 6u);
	const int expectedLines[] = {6, 7, 8, 9, 16, 17};
	const Label expectedLabels[] = {Label::Wall,        Label::Door,
	                                Label::Wastebasket, Label::Washbasin,
	                                Label::Stairs,      Label::Grass};
	for (std::size_t i = 0; i < s.objects.size(); i++)
	{
		EXPECT_EQ(s.objects[i].id, static_cast<int>(i) + 1);
		EXPECT_EQ(s.objects[i].line, expectedLines[i]) << "object " << i;
		EXPECT_EQ(s.objects[i].label, expectedLabels[i]) << "object " << i;
		EXPECT_EQ(s.objects[i].parts.size(), i == 3 ? 2u : 1u);
	}

	const auto& wall = partAs<BoxShape>(s, 0);
	EXPECT_DOUBLE_EQ(wall.center.x, 5);
	EXPECT_DOUBLE_EQ(wall.center.y, 0.05);
	EXPECT_DOUBLE_EQ(wall.center.z, 1.25);
	EXPECT_DOUBLE_EQ(wall.size.x, 10);
	EXPECT_DOUBLE_EQ(wall.size.y, 0.1);
	EXPECT_DOUBLE_EQ(wall.size.z, 2.5);
	EXPECT_DOUBLE_EQ(wall.yaw, 30 * kDeg);

	const auto& door = partAs<BoxShape>(s, 1);
	EXPECT_DOUBLE_EQ(door.center.x, 3);
	EXPECT_DOUBLE_EQ(door.size.y, 0.04);
	EXPECT_DOUBLE_EQ(door.yaw, 0);  // default

	const auto& bin = partAs<CylinderShape>(s, 2);
	EXPECT_DOUBLE_EQ(bin.center.x, 1.5);
	EXPECT_DOUBLE_EQ(bin.center.y, 1.0);
	EXPECT_DOUBLE_EQ(bin.center.z, 0.2);
	EXPECT_DOUBLE_EQ(bin.radius, 0.15);
	EXPECT_DOUBLE_EQ(bin.height, 0.4);

	const auto& basin = partAs<BoxShape>(s, 3, 0);
	EXPECT_DOUBLE_EQ(basin.center.z, 0.8);
	EXPECT_DOUBLE_EQ(basin.size.x, 0.5);
	EXPECT_DOUBLE_EQ(basin.size.z, 0.15);
	EXPECT_DOUBLE_EQ(basin.yaw, -90 * kDeg);
	const auto& pedestal = partAs<CylinderShape>(s, 3, 1);
	EXPECT_DOUBLE_EQ(pedestal.center.y, 0.25);
	EXPECT_DOUBLE_EQ(pedestal.radius, 0.08);
	EXPECT_DOUBLE_EQ(pedestal.height, 0.8);

	const auto& st = partAs<StairsShape>(s, 4);
	EXPECT_DOUBLE_EQ(st.origin.x, 8);
	EXPECT_DOUBLE_EQ(st.origin.y, 4);
	EXPECT_DOUBLE_EQ(st.yaw, M_PI / 2);
	EXPECT_EQ(st.steps, 5);
	EXPECT_DOUBLE_EQ(st.rise, 0.17);
	EXPECT_DOUBLE_EQ(st.run, 0.28);
	EXPECT_DOUBLE_EQ(st.width, 1.2);

	const auto& grass = partAs<TerrainShape>(s, 5);
	ASSERT_EQ(grass.polygon.size(), 4u);
	EXPECT_DOUBLE_EQ(grass.polygon[2].x, 5);
	EXPECT_DOUBLE_EQ(grass.polygon[2].y, 3);
	EXPECT_DOUBLE_EQ(grass.roughness, 0.03);

	EXPECT_DOUBLE_EQ(s.sensor.mount.x, 0.1);
	EXPECT_DOUBLE_EQ(s.sensor.mount.y, -0.05);
	EXPECT_DOUBLE_EQ(s.sensor.mount.z, 0.5);
	EXPECT_DOUBLE_EQ(s.sensor.phiMin, -60 * kDeg);
	EXPECT_DOUBLE_EQ(s.sensor.phiMax, 60 * kDeg);
	EXPECT_DOUBLE_EQ(s.sensor.phiStep, 1 * kDeg);
	EXPECT_DOUBLE_EQ(s.sensor.thetaMin, -10 * kDeg);
	EXPECT_DOUBLE_EQ(s.sensor.thetaMax, 80 * kDeg);
	EXPECT_DOUBLE_EQ(s.sensor.thetaStep, 0.25 * kDeg);
	EXPECT_DOUBLE_EQ(s.sensor.maxRange, 6.5);
	EXPECT_DOUBLE_EQ(s.sensor.rangeNoise, 0.01);
	EXPECT_EQ(s.sensor.beamCount(), 121u);
	EXPECT_EQ(s.sensor.lineCount(), 361u);

	EXPECT_DOUBLE_EQ(s.odometry.transNoise, 0.03);
	EXPECT_DOUBLE_EQ(s.odometry.rotNoisePerM, 1.5 * kDeg);
	EXPECT_DOUBLE_EQ(s.odometry.rotBiasPerM, -3.5 * kDeg);

	ASSERT_EQ(s.trajectory.size(), 3u);
	EXPECT_DOUBLE_EQ(s.trajectory[1].x, 3.0);
	EXPECT_DOUBLE_EQ(s.trajectory[1].y, 4.5);
	EXPECT_DOUBLE_EQ(s.trajectory[1].phi, M_PI / 2);
	EXPECT_DOUBLE_EQ(s.trajectory[2].phi, -M_PI / 4);
}

TEST(SceneLoader, DefaultsWhenOptionalSectionsAbsent)
{
	const Scene s = SceneLoader::parse(edited(0, ""), "t.yaml");
	EXPECT_FALSE(s.ceilingHeight.has_value());
	const SensorSpec d;
	EXPECT_DOUBLE_EQ(s.sensor.mount.z, 0.45);
	EXPECT_DOUBLE_EQ(s.sensor.phiMin, -M_PI / 2);
	EXPECT_DOUBLE_EQ(s.sensor.phiMax, M_PI / 2);
	EXPECT_DOUBLE_EQ(s.sensor.phiStep, 0.5 * kDeg);
	EXPECT_DOUBLE_EQ(s.sensor.thetaMin, -15 * kDeg);
	EXPECT_DOUBLE_EQ(s.sensor.thetaMax, 90 * kDeg);
	EXPECT_DOUBLE_EQ(s.sensor.thetaStep, d.thetaStep);
	EXPECT_DOUBLE_EQ(s.sensor.maxRange, 8.0);
	EXPECT_DOUBLE_EQ(s.sensor.rangeNoise, 0.005);
	EXPECT_EQ(s.sensor.beamCount(), 361u);
	EXPECT_EQ(s.sensor.lineCount(), 211u);
	EXPECT_DOUBLE_EQ(s.odometry.transNoise, 0.02);
	EXPECT_DOUBLE_EQ(s.odometry.rotNoisePerM, 2.0 * kDeg);
	EXPECT_DOUBLE_EQ(s.odometry.rotBiasPerM, 0.0);
	ASSERT_EQ(s.objects.size(), 1u);
	EXPECT_EQ(s.objects[0].id, 1);
	EXPECT_EQ(s.objects[0].line, 4);
}

TEST(SceneLoader, SensorKeysAreIndividuallyOptional)
{
	const Scene s =
	    SceneLoader::parse(appended("sensor: {max_range: 4}"), "t.yaml");
	EXPECT_DOUBLE_EQ(s.sensor.maxRange, 4);
	EXPECT_EQ(s.sensor.beamCount(), 361u);
	EXPECT_DOUBLE_EQ(s.sensor.rangeNoise, 0.005);
}

TEST(SceneLoader, ObjectsMayBeAbsent)
{
	const Scene s = SceneLoader::parse(
	    "name: empty\nbounds: [0, 0, 1, 1]\ntrajectory: [[0.5, 0.5, 0]]\n",
	    "t.yaml");
	EXPECT_TRUE(s.objects.empty());
	EXPECT_EQ(s.trajectory.size(), 1u);
}

TEST(SceneLoaderErrors, UnknownTopLevelKey)
{
	expectError(
	    appended("colour: red"), 7, "colour",
	    "unknown key (allowed: name, bounds, ceiling_height, objects, "
	    "sensor, odometry, trajectory)");
}

TEST(SceneLoaderErrors, UnknownObjectKey)
{
	expectError(
	    edited(
	        4,
	        "  - {label: wall, colour: red, box: {center: [1, 1, 1], size: "
	        "[1, 1, 2]}}"),
	    4, "objects[0].colour", "unknown key (allowed: label, box,");
}

TEST(SceneLoaderErrors, UnknownBoxKey)
{
	expectError(
	    edited(
	        4,
	        "  - {label: wall, box: {center: [1, 1, 1], size: [1, 1, 2], "
	        "pitch: 3}}"),
	    4, "objects[0].box.pitch", "unknown key (allowed: center, size, yaw)");
}

TEST(SceneLoaderErrors, UnknownKeyInNestedBlock)
{
	expectError(
	    appended("sensor:\n  mount: [0, 0, 0.4]\n  fov: 180"), 9, "sensor.fov",
	    "unknown key (allowed: mount, phi, theta, max_range, range_noise)");
	expectError(
	    appended("odometry:\n  trans_noise: 0.1\n  rot_noise: 2"), 9,
	    "odometry.rot_noise", "allowed: trans_noise, rot_noise_deg_per_m");
}

TEST(SceneLoaderErrors, DuplicateKey)
{
	expectError(appended("name: again"), 7, "name", "duplicate key");
}

TEST(SceneLoaderErrors, MissingRequiredKey)
{
	expectError(edited(1, "# no name"), 2, "name", "missing required key");
	expectError(
	    edited(4, "  - {label: wall, box: {center: [1, 1, 1]}}"), 4,
	    "objects[0].box.size", "missing required key");
	expectError(
	    edited(4, "  - {box: {center: [1, 1, 1], size: [1, 1, 2]}}"), 4,
	    "objects[0].label", "missing required key");
	expectError(firstLines(4), 1, "trajectory", "missing required key");
	expectError(
	    edited(4, "  - {label: wall}"), 4, "objects[0]",
	    "missing shape: expected one of box, cylinder, stairs, terrain, parts");
}

TEST(SceneLoaderErrors, TwoShapesInOneObject)
{
	expectError(
	    edited(
	        4,
	        "  - {label: wall, box: {center: [1, 1, 1], size: [1, 1, 2]}, "
	        "cylinder: {center: [1, 1, 1], radius: 1, height: 1}}"),
	    4, "objects[0]", "got box and cylinder");
	expectError(
	    edited(
	        4,
	        "  - label: washbasin\n"
	        "    parts:\n"
	        "      - {cylinder: {center: [1, 1, 1], radius: 1, height: 1}}\n"
	        "      - {box: {center: [1, 1, 1], size: [1, 1, 2]}, terrain: "
	        "{polygon: [[0, 0], [1, 0], [1, 1]], roughness: 0}}"),
	    7, "objects[0].parts[1]", "got box and terrain");
}

TEST(SceneLoaderErrors, WrongType)
{
	expectError(
	    edited(
	        4,
	        "  - {label: wall, box: {center: [1, 1, 1], size: [1, one, 2]}}"),
	    4, "objects[0].box.size[1]", "expected a number, got 'one'");
	expectError(
	    edited(
	        4,
	        "  - {label: wall, box: {center: [1, 1, 1], size: [1, 1, 2], yaw: "
	        "\"90\"}}"),
	    4, "objects[0].box.yaw", "expected a number, got string '90'");
	expectError(
	    edited(4, "  - {label: wall, box: [1, 1, 1]}"), 4, "objects[0].box",
	    "expected a map, got a list");
	expectError(
	    edited(2, "bounds: {xmin: 0}"), 2, "bounds",
	    "expected a list of 4 numbers, got a map");
	expectError(
	    appended("ceiling_height: true"), 7, "ceiling_height",
	    "expected a number, got 'true'");
	expectError(
	    firstLines(2) + "objects: {a: 1}\ntrajectory: [[1, 2, 0]]\n", 3,
	    "objects", "expected a list, got a map");
	expectError(
	    edited(
	        4,
	        "  - {label: stairs, stairs: {origin: [1, 1], steps: 2.5, rise: "
	        "0.2, run: 0.3, width: 1}}"),
	    4, "objects[0].stairs.steps", "expected an integer, got 2.5");
}

TEST(SceneLoaderErrors, WrongListLength)
{
	expectError(
	    edited(4, "  - {label: wall, box: {center: [1, 1, 1], size: [1, 1]}}"),
	    4, "objects[0].box.size", "expected 3 numbers, got 2");
	expectError(
	    edited(6, "  - [1, 2]"), 6, "trajectory[0]",
	    "expected 3 numbers, got 2");
	expectError(
	    edited(2, "bounds: [0, 0, 10]"), 2, "bounds",
	    "expected 4 numbers, got 3");
}

TEST(SceneLoaderErrors, NegativeOrZeroSize)
{
	expectError(
	    edited(
	        4, "  - {label: wall, box: {center: [1, 1, 1], size: [1, -1, 2]}}"),
	    4, "objects[0].box.size[1]", "must be > 0, got -1");
	expectError(
	    edited(
	        4,
	        "  - label: washbasin\n"
	        "    parts:\n"
	        "      - cylinder:\n"
	        "          center: [1, 1, 1]\n"
	        "          radius: 0\n"
	        "          height: 1"),
	    8, "objects[0].parts[0].cylinder.radius", "must be > 0, got 0");
	expectError(
	    edited(
	        4,
	        "  - {label: stairs, stairs: {origin: [1, 1], steps: 0, rise: "
	        "0.2, run: 0.3, width: 1}}"),
	    4, "objects[0].stairs.steps", "must be in [1, 1000], got 0");
}

TEST(SceneLoaderErrors, HugeStairsAreBoundedBeforeAllocating)
{
	// 1e8 steps ran the simulator out of memory (std::bad_alloc) after 17 s.
	expectError(
	    edited(
	        4,
	        "  - {label: stairs, stairs: {origin: [5, 5], steps: 100000000, "
	        "rise: 0.1, run: 0.3, width: 1}}"),
	    4, "objects[0].stairs.steps", "must be in [1, 1000], got 100000000");
}

TEST(SceneLoaderErrors, AbsurdSizesAndCoordinatesNameTheLimit)
{
	expectError(
	    edited(
	        4,
	        "  - {label: wall, box: {center: [1, 1, 1], size: [1e30, 1, 2]}}"),
	    4, "objects[0].box.size[0]", "must be at most 1000 m, got 1e+30");
	expectError(
	    edited(
	        4,
	        "  - {label: wastebasket, cylinder: {center: [1, 1, 0.2], radius: "
	        "0.1, height: 5000}}"),
	    4, "objects[0].cylinder.height", "must be at most 1000 m");
	expectError(
	    edited(
	        4,
	        "  - {label: wall, box: {center: [1, -1e30, 1], size: [1, 1, 2]}}"),
	    4, "objects[0].box.center[1]", "must lie within +-10000 m, got -1e+30");
	expectError(
	    edited(2, "bounds: [0, 0, 1e30, 10]"), 2, "bounds[2]",
	    "must lie within +-10000 m");
	expectError(
	    appended("ceiling_height: 1e12"), 7, "ceiling_height",
	    "must be at most 1000 m");
	expectError(
	    appended("sensor: {max_range: 1e9}"), 7, "sensor.max_range",
	    "must be at most 1000 m");
	expectError(
	    edited(
	        4,
	        "  - {label: grass, terrain: {polygon: [[0, 0], [1, 0], [1, 1]], "
	        "roughness: 1e20}}"),
	    4, "objects[0].terrain.roughness", "must be at most 1000 m");
}

TEST(SceneLoaderErrors, UnknownLabel)
{
	expectError(
	    edited(
	        4, "  - {label: chair, box: {center: [1, 1, 1], size: [1, 1, 2]}}"),
	    4, "objects[0].label", "unknown label 'chair' (known: floor,");
	expectError(
	    edited(
	        4,
	        "  - {label: unknown, box: {center: [1, 1, 1], size: [1, 1, 2]}}"),
	    4, "objects[0].label", "'unknown' is not allowed");
}

TEST(SceneLoader, ARegisteredClassIsALabel)
{
	ClassInfo c;
	c.name = "chair";
	const Label chair = ClassRegistry::instance().add(c);
	const Scene s = SceneLoader::parse(
	    edited(
	        4,
	        "  - {label: chair, box: {center: [1, 1, 0.4], size: [0.5, 0.5, "
	        "0.8]}}"),
	    "t.yaml");
	ClassRegistry::instance().resetToBuiltIns();
	ASSERT_FALSE(s.objects.empty());
	EXPECT_EQ(s.objects[0].label, chair);
}

TEST(SceneLoaderErrors, PolygonWithTwoVertices)
{
	expectError(
	    edited(
	        4,
	        "  - label: grass\n"
	        "    terrain:\n"
	        "      roughness: 0.03\n"
	        "      polygon: [[0, 0], [1, 1]]"),
	    7, "objects[0].terrain.polygon", "expected at least 3 vertices, got 2");
	expectError(
	    edited(
	        4,
	        "  - {label: grass, terrain: {polygon: [[0, 0], [1, 1], [2, 2]], "
	        "roughness: 0}}"),
	    4, "objects[0].terrain.polygon", "degenerate polygon");
	expectError(
	    edited(
	        4,
	        "  - {label: grass, terrain: {polygon: [[0, 0], [1, 0], [1, 1]], "
	        "roughness: -0.1}}"),
	    4, "objects[0].terrain.roughness", "must be >= 0, got -0.1");
}

TEST(SceneLoaderErrors, SensorAngleRanges)
{
	expectError(
	    appended("sensor:\n  theta: [30, 10, 0.5]"), 8, "sensor.theta",
	    "min must be < max, got min 30, max 10");
	expectError(
	    appended("sensor:\n  theta: [10, 10, 0.5]"), 8, "sensor.theta",
	    "min must be < max");
	expectError(
	    appended("sensor:\n  theta: [-15, 95, 0.5]"), 8, "sensor.theta",
	    "must lie within [-90, 90] deg");
	expectError(
	    appended("sensor: {phi: [-190, 90, 0.5]}"), 7, "sensor.phi",
	    "must lie within [-180, 180] deg");
	expectError(
	    appended("sensor: {phi: [-90, 90, 0]}"), 7, "sensor.phi",
	    "step must be >= 0.1 deg, got 0");
	// A 1e-5 deg step failed later in an OpenCV allocation naming no key.
	expectError(
	    appended("sensor: {phi: [-90, 90, 0.00001]}"), 7, "sensor.phi",
	    "step must be >= 0.1 deg, got 1e-05");
	expectError(
	    appended("sensor: {theta: [-10, 80, 0.001]}"), 7, "sensor.theta",
	    "step must be >= 0.1 deg");
	expectError(
	    appended("sensor: {max_range: 0}"), 7, "sensor.max_range",
	    "must be > 0");
	expectError(
	    appended("odometry: {trans_noise: -0.1}"), 7, "odometry.trans_noise",
	    "must be >= 0");
}

TEST(SceneLoaderErrors, BadBoundsAndPoses)
{
	expectError(
	    edited(2, "bounds: [0, 0, 0, 10]"), 2, "bounds",
	    "expected xmin < xmax and ymin < ymax");
	expectError(
	    edited(6, "  - [1, 2, 0]\n  - [11, 2, 0]"), 7, "trajectory[1]",
	    "outside the bounds");
	expectError(
	    appended("ceiling_height: -2"), 7, "ceiling_height", "must be > 0");
	expectError(edited(1, "name: a/b"), 1, "name", "not a valid file name");
}

TEST(SceneLoaderErrors, PoseInsideAnObstacle)
{
	// The base scene's wall spans x, y in [0.5, 1.5].
	expectError(
	    edited(6, "  - [1, 2, 0]\n  - [1.2, 0.9, 0]"), 7, "trajectory[1]",
	    "pose (1.2, 0.9) is inside objects[0] (wall, line 4)");
	const std::string wall = kBaseLines[3] + "\n";
	std::string stairs = edited(
	    4, wall +
	           "  - {label: stairs, stairs: {origin: [5, 5], yaw: 90, "
	           "steps: 3, rise: 0.2, run: 0.3, width: 1}}");
	stairs.replace(stairs.find("[1, 2, 0]"), 9, "[5.2, 5.5, 0]");
	expectError(
	    stairs, 7, "trajectory[0]", "inside objects[1] (stairs, line 5)");
	// Over a mat and under a table top the robot stands free.
	EXPECT_EQ(
	    errorOf(edited(
	        4, wall + "  - {label: obstacle, box: {center: [1, 2, 0.01], size: "
	                  "[1, 1, 0.02]}}\n"
	                  "  - {label: obstacle, box: {center: [1, 2, 0.75], size: "
	                  "[1, 1, 0.04]}}")),
	    "(no error)");
}

TEST(SceneLoaderErrors, EmptyTrajectory)
{
	expectError(edited(6, ""), 5, "trajectory", "expected a list, got null");
	expectError(
	    firstLines(4) + "trajectory: []\n", 5, "trajectory",
	    "expected at least 1 pose, got 0");
}

TEST(SceneLoaderErrors, TooManyObjects)
{
	std::string yaml = "name: t\nbounds: [0, 0, 10, 10]\nobjects:\n";
	for (int i = 0; i < 256; i++)
		yaml +=
		    "  - {label: obstacle, cylinder: {center: [1, 1, 0.5], "
		    "radius: 0.1, height: 1}}\n";
	yaml += "trajectory: [[5, 5, 0]]\n";
	expectError(yaml, 259, "objects[255]", "too many objects: 256");
	// 255 is fine, ids 1..255
	const auto cut = yaml.rfind("  - {label");
	const std::string ok = yaml.substr(0, cut) + "trajectory: [[5, 5, 0]]\n";
	const Scene s = SceneLoader::parse(ok, "t.yaml");
	ASSERT_EQ(s.objects.size(), 255u);
	EXPECT_EQ(s.objects.back().id, 255);
	EXPECT_EQ(s.objects.back().line, 258);
}

TEST(SceneLoaderErrors, YamlSyntaxError)
{
	expectError(
	    edited(
	        4, "  - {label: wall, box: {center: [1, 1, 1], size: [1, 1, 2]}"),
	    6, "", "YAML syntax error");
	expectError(appended("foo: bar: baz"), 7, "", "YAML syntax error");
}

TEST(SceneLoaderErrors, NotASceneMap)
{
	EXPECT_NE(errorOf("").find("t.yaml:1: "), std::string::npos);
	expectError("- 1\n- 2\n", 1, "", "expected a scene map");
	expectError(edited(0, "") + "---\nname: x\n", 8, "", "one YAML document");
}

// Found by fuzz_scene (fuzz/): on this text (a stray '}') yaml-cpp's
// LoadAll() made empty documents without end, until memory ran out.
TEST(SceneLoaderErrors, StrayBraceEndsInAnError)
{
	std::ifstream f(
	    std::string(SEMNAV_SOURCE_DIR) +
	    "/tests/sim/data/fuzz-scene-stray-brace.yaml");
	ASSERT_TRUE(f.good());
	const std::string text(std::istreambuf_iterator<char>(f), {});
	EXPECT_EQ(errorOf(text).rfind("t.yaml:", 0), 0u) << errorOf(text);
}

TEST(SceneLoaderErrors, MissingFile)
{
	try
	{
		SceneLoader::loadFile("/nonexistent/dir/scene.yaml");
		FAIL() << "no exception";
	}
	catch (const SceneError& e)
	{
		EXPECT_STREQ(
		    e.what(), "cannot open scene file /nonexistent/dir/scene.yaml");
	}
}

TEST(SceneLoader, LoadFileNamesTheFileInErrors)
{
	const auto path = std::filesystem::temp_directory_path() /
	                  "semnav_scene_loader_test.yaml";
	{
		std::ofstream f(path);
		f << edited(
		    4, "  - {label: wall, box: {center: [1, 1], size: [1, 1, 2]}}");
	}
	try
	{
		SceneLoader::loadFile(path.string());
		FAIL() << "no exception";
	}
	catch (const SceneError& e)
	{
		EXPECT_EQ(
		    std::string(e.what()),
		    path.string() +
		        ":4: objects[0].box.center: expected 3 numbers, got 2");
	}
	std::filesystem::remove(path);
}
