/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/sim/Scene.h>

namespace semnav
{
class SemanticMap;

/** Ground-truth semantic map of a scene, for tests and benchmarks that must
 * not depend on perception or detection quality: every cell inside the
 * scene bounds is observed; a cell is occupied when a primitive whose
 * height range overlaps [obstacle_min_height, robot_height] of the map
 * covers its centre (label of that object), free otherwise (floor, or the
 * terrain patch's label). Objects of the labels door, stairs, washbasin
 * and wastebasket become map instances (SemanticMap::addInstance) with
 * their 2D footprint, in scene order, counted as seen in 1000 sweeps so
 * that any min_observations reports them. */
class SceneMapBuilder
{
public:
	/** Fills an empty map (its options give resolution and heights). */
	static void build(const Scene& scene, SemanticMap& map);
	/** Adds the scene's objects of `label` as instances of `map` (e.g. to a
	 * map built by semnav-map before the detectors find them). Returns how
	 * many were added. */
	static int addInstances(const Scene& scene, Label label, SemanticMap& map);
	/** 2D footprint bounds (xmin, ymin, zmin) - (xmax, ymax, zmax) of an
	 * object. */
	static void bounds(
	    const SceneObject& o, mrpt::math::TPoint3D& lo,
	    mrpt::math::TPoint3D& hi);
};

}  // namespace semnav
