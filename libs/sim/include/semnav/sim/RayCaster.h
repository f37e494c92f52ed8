/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/math/TPoint3D.h>
#include <semnav/common/Label.h>
#include <semnav/sim/Scene.h>

#include <cstdint>
#include <memory>
#include <vector>

namespace semnav
{
/** Result of RayCaster::cast(). */
struct RayHit
{
	bool hit = false;
	/** Distance from the ray origin to the hit point (m); 0 on a miss. */
	double range = 0;
	Label label = Label::Unknown;
	/** SceneObject::id of the object hit; 0 for floor, ceiling and misses. */
	int instance = 0;
};

/** Exact ray casting against a Scene.
 *
 * Surfaces (all solid, seen from outside):
 * - floor: plane z = 0 inside scene.bounds (label floor, instance 0), except
 *   inside terrain polygons;
 * - ceiling: plane z = ceilingHeight inside scene.bounds (label ceiling);
 * - oriented boxes (slab test in the box frame), vertical cylinders (side
 *   and caps), stairs (one solid box per step, as Scene.h says);
 * - terrain: a ground patch replacing the floor inside its polygon. Its
 *   height is a bilinearly interpolated field on a square grid of
 *   `terrainCell` m holding zero-mean Gaussian heights (generated from the
 *   seed), multiplied by a taper that grows linearly from 0 on the polygon
 *   boundary to 1 at kTerrainTaperCells cells inside, so the patch joins the
 *   floor. Node heights have std dev 1.5 * roughness so that the RMS height
 *   of the interpolated surface (bilinear interpolation of i.i.d. nodes has
 *   mean variance 4/9 of the nodes') equals `roughness`. The ray is marched
 *   cell by cell, only through the cells whose height range it crosses
 *   (inside the patch's z band). In a cell the surface is bilinear, so the
 *   height above it is a quadratic along the ray and its first root is
 *   bracketed exactly (dips under a bump included); in tapered boundary
 *   cells the ray is sampled every quarter cell. The crossing is refined by
 *   bisection to < 0.01 mm. A root within 1 mm outside the polygon still
 *   counts as terrain, so no ray slips between terrain and floor.
 *
 * A ray starting inside a solid does not hit that solid. The nearest hit
 * wins; exact ties go to the first primitive in scene order (floor and
 * ceiling first), so the accelerated and brute-force modes return identical
 * results. cast() is const and thread-safe. */
class RayCaster
{
public:
	enum class Mode
	{
		/** Bounding-volume hierarchy over primitive boxes, nearest-first. */
		Accelerated,
		/** Every primitive tested exactly, no culling (test oracle and
		 * benchmark baseline). */
		BruteForce
	};

	/** Taper width of terrain patches, in grid cells. */
	static constexpr double kTerrainTaperCells = 3.0;

	/** Builds the primitives; `seed` drives the terrain heights. Throws
	 * SceneError for degenerate primitives (non-positive sizes, polygons
	 * with < 3 vertices) and terrain patches of more than 2e7 cells (before
	 * allocating them), and Error for terrainCell <= 0. */
	explicit RayCaster(
	    const Scene& scene, uint64_t seed = 0, double terrainCell = 0.1);
	~RayCaster();
	RayCaster(RayCaster&&) noexcept;
	RayCaster& operator=(RayCaster&&) noexcept;
	RayCaster(const RayCaster&) = delete;
	RayCaster& operator=(const RayCaster&) = delete;

	/** Nearest hit along origin + t * unitDir, 0 <= t <= maxRange.
	 * `unitDir` must have unit length. */
	RayHit cast(
	    const mrpt::math::TPoint3D& origin, const mrpt::math::TPoint3D& unitDir,
	    double maxRange) const;

	void setMode(Mode m) { m_mode = m; }
	Mode mode() const { return m_mode; }

	/** Ground height at (x, y): the terrain height inside a terrain polygon
	 * (the first one in scene order), 0 elsewhere. */
	double groundHeight(double x, double y) const;

	/** Number of primitives (stairs count one per step; floor and ceiling
	 * not included). */
	std::size_t primitiveCount() const;
	/** Largest SceneObject::id in the scene (0 if none). */
	int maxInstanceId() const { return m_maxInstance; }

private:
	struct Impl;
	std::unique_ptr<Impl> m_impl;
	Mode m_mode = Mode::Accelerated;
	int m_maxInstance = 0;
};

}  // namespace semnav
