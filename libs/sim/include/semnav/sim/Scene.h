/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/math/TPoint2D.h>
#include <mrpt/math/TPoint3D.h>
#include <mrpt/math/TPose2D.h>
#include <semnav/common/Label.h>

#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace semnav
{
/** Scene model read from the scene YAML of docs/design.md. World frame: x, y on
 * the floor (z = 0), z up. Lengths in metres, angles in radians (the YAML
 * has degrees; the loader converts). */

/** Oriented box: centre (z included), full size along its own x, y, z, and
 * yaw about the vertical axis. */
struct BoxShape
{
	mrpt::math::TPoint3D center;
	mrpt::math::TPoint3D size;
	double yaw = 0;
};

/** Vertical cylinder: centre at mid-height. */
struct CylinderShape
{
	mrpt::math::TPoint3D center;
	double radius = 0;
	double height = 0;
};

/** Solid straight stairs: `origin` is the foot of the first step, centre of
 * its width; the stairs climb along `yaw`. Step k (0-based) is a solid block
 * of height (k+1)*rise spanning [k*run, (k+1)*run] along the climb. */
struct StairsShape
{
	mrpt::math::TPoint2D origin;
	double yaw = 0;
	int steps = 0;
	double rise = 0;
	double run = 0;
	double width = 0;
};

/** A patch of ground (replacing the floor inside `polygon`) with random
 * height bumps of standard deviation `roughness` (m). */
struct TerrainShape
{
	std::vector<mrpt::math::TPoint2D> polygon;
	double roughness = 0;
};

using ScenePrimitive =
    std::variant<BoxShape, CylinderShape, StairsShape, TerrainShape>;

/** One labelled object: one primitive, or several (`parts:`). */
struct SceneObject
{
	Label label = Label::Unknown;
	std::vector<ScenePrimitive> parts;
	/** Instance id written to ground-truth images: 1-based position in the
	 * scene's object list (0 = no object: floor, ceiling). */
	int id = 0;
	/** Line of the object in the scene file (1-based; 0 if unknown). */
	int line = 0;

	/** Floor position (x, y) of the object, as the map's objects are scored:
	 * a door's is the mean of its parts' centres (both leaves of a double
	 * door); any other object's is its first part's footprint centre (a
	 * washbasin's basin, a staircase's flight). (0, 0) for terrain. */
	mrpt::math::TPoint2D centre() const;
};

/** The LMS200 on a tilting head; defaults are the paper's. */
struct SensorSpec
{
	/** Tilt-axis position in the robot frame. */
	mrpt::math::TPoint3D mount{0.0, 0.0, 0.45};
	double phiMin = -M_PI / 2, phiMax = M_PI / 2, phiStep = 0.5 * M_PI / 180;
	double thetaMin = -15 * M_PI / 180, thetaMax = 90 * M_PI / 180,
	       thetaStep = 0.5 * M_PI / 180;
	double maxRange = 8.0;
	/** Gaussian range noise std dev, m (LMS200 mm mode). */
	double rangeNoise = 0.005;

	std::size_t beamCount() const;
	std::size_t lineCount() const;
};

/** Odometry error model, applied per motion between two stops. */
struct OdometrySpec
{
	/** Translation error std dev per metre travelled (m/m). */
	double transNoise = 0.02;
	/** Heading error std dev per metre travelled (rad/m). */
	double rotNoisePerM = 2.0 * M_PI / 180;
	/** Systematic heading drift per metre travelled (rad/m). */
	double rotBiasPerM = 0.0;
};

struct SceneBounds
{
	double xmin = 0, ymin = 0, xmax = 0, ymax = 0;
	bool contains(double x, double y) const
	{
		return x >= xmin && x <= xmax && y >= ymin && y <= ymax;
	}
};

struct Scene
{
	std::string name;
	/** Floor extent (label floor). */
	SceneBounds bounds;
	/** Ceiling plane over the bounds (label ceiling), if any. */
	std::optional<double> ceilingHeight;
	std::vector<SceneObject> objects;
	SensorSpec sensor;
	OdometrySpec odometry;
	/** Stop-and-scan poses (x, y, yaw in rad); one sweep at each. */
	std::vector<mrpt::math::TPose2D> trajectory;

	/** Lowest height (m) of the robot's body: solids below it (thresholds,
	 * mats) are driven over. */
	static constexpr double kBodyBottom = 0.05;

	/** Index in `objects` of the first object with a solid part (box,
	 * cylinder, stairs step; terrain is ground) where a robot centred at
	 * (x, y) would stand: a part reaching into the robot's body, from
	 * kBodyBottom up to the sensor's mount height. Nothing if none. */
	std::optional<std::size_t> obstacleAt(double x, double y) const;
};

}  // namespace semnav
