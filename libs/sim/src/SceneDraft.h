/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once
// A scene being generated (src/ only): its objects, their floor footprints,
// keep-out lanes, the trajectory, and the scene file's text.

#include <semnav/common/Label.h>

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "GeneratorGeometry.h"

namespace semnav::detail
{
/** One primitive of a generated object (angles in degrees, as in the file). */
struct DraftPart
{
	enum class Kind
	{
		Box,
		Cylinder,
		Stairs
	};
	Kind kind = Kind::Box;
	double x = 0, y = 0, z = 0;  ///< box/cylinder centre; stairs origin (x, y)
	double sx = 0, sy = 0, sz = 0;  ///< box size
	double yawDeg = 0;              ///< box and stairs
	double radius = 0, height = 0;  ///< cylinder
	int steps = 0;                  ///< stairs
	double rise = 0, run = 0, width = 0;

	static DraftPart box(
	    double x, double y, double z, double sx, double sy, double sz,
	    double yawDeg = 0);
	static DraftPart cylinder(
	    double x, double y, double z, double radius, double height);
	static DraftPart stairs(
	    double x, double y, double yawDeg, int steps, double rise, double run,
	    double width);
	/** Floor footprint; empty when the part starts above `maxBottom`. */
	Polygon2D footprint(double maxBottom) const;
};

/** Deterministic random numbers: std::mt19937_64 (its output is fixed by the
 * standard) mapped to doubles by hand, so the same seed gives the same scene
 * on every standard library. */
class GeneratorRandom
{
public:
	explicit GeneratorRandom(uint64_t seed) : m_engine(seed) {}
	double uniform(double lo, double hi);
	/** Integer in [lo, hi]. */
	int uniformInt(int lo, int hi);
	bool chance(double p) { return uniform(0, 1) < p; }

private:
	std::mt19937_64 m_engine;
};

class SceneDraft
{
public:
	/** Objects starting above this height are not obstacles to the robot. */
	static constexpr double kObstacleTop = 1.2;

	SceneDraft(std::string name, uint64_t seed);

	GeneratorRandom& rng() { return m_rng; }
	void addComment(const std::string& line) { m_comments.push_back(line); }
	void setBounds(double xmin, double ymin, double xmax, double ymax);
	void setCeiling(double h) { m_ceiling = h; }
	void setOdometryBias(double degPerM) { m_rotBias = degPerM; }

	/** Adds an object of one or more parts. A `structural` one (walls,
	 * doors) keeps poses clear but furniture may touch it. */
	void add(
	    Label label, const std::vector<DraftPart>& parts,
	    bool structural = false);
	void addTerrain(Label label, const Polygon2D& polygon, double roughness);
	/** A lane (capsule of `radius` around segment ab) furniture stays out of.
	 */
	void addKeepOut(
	    const mrpt::math::TPoint2D& a, const mrpt::math::TPoint2D& b,
	    double radius);

	/** Whether `fp` is at least `margin` from every non-structural obstacle
	 * footprint, does not overlap a structural one, and is outside every
	 * keep-out lane. */
	bool isFree(const Polygon2D& fp, double margin) const;
	/** Whether every part of `parts` is free (isFree). */
	bool isFree(const std::vector<DraftPart>& parts, double margin) const;
	/** Distance from segment ab (a point when a == b) to the nearest
	 * obstacle footprint. */
	double clearance(
	    const mrpt::math::TPoint2D& a, const mrpt::math::TPoint2D& b) const;

	void addPose(double x, double y, double yawDeg);
	std::size_t poseCount() const { return m_poses.size(); }
	/** Empty when every pose is `poseClearance` from all obstacles and inside
	 * the bounds and every path between stops `pathClearance`; else what is
	 * wrong. */
	std::string trajectoryProblem(
	    double poseClearance, double pathClearance) const;

	/** The scene file's text. */
	std::string yaml() const;

private:
	struct Pose
	{
		double x, y, yawDeg;
	};
	struct KeepOut
	{
		mrpt::math::TPoint2D a, b;
		double radius;
	};
	std::string m_name;
	GeneratorRandom m_rng;
	std::vector<std::string> m_comments;
	double m_bounds[4] = {0, 0, 0, 0};
	double m_ceiling = 0;
	double m_rotBias = 0;
	std::vector<std::string> m_objects;
	std::vector<Polygon2D> m_footprints;
	std::vector<bool> m_structural;  ///< per footprint
	std::vector<KeepOut> m_keepOuts;
	std::vector<Pose> m_poses;
};

/** A number as written in generated files: millimetres, no trailing zeros,
 * never "-0". */
std::string formatNumber(double v);

}  // namespace semnav::detail
