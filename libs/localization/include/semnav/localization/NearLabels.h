/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/poses/CPose2D.h>
#include <semnav/common/GridGeometry.h>
#include <semnav/common/LabelSet.h>

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace semnav
{
class LabeledSweep;

/** Mapping: the labels each map cell received from pixels within a range of
 * the robot that saw them (the union over sweeps, as the map's "labels"
 * layer, but of near views only). The ground types far from the sensor are
 * the least reliable (outdoors, sidewalk seen from 5-6 m is labelled grass
 * several times as often as from 2-3 m), and while mapping the first views
 * of a place are often the far ones: scored against such a layer, a sweep's
 * correct near labels pull the estimate toward where the far labels put the
 * border. SemanticEvidenceMap scores the ground points against this layer
 * instead (cells without a near label are unknown).
 *
 * Cells are anchored in the world (floor(x / resolution)), so the layer
 * follows the map's growth. */
class NearLabels
{
public:
	/** `range`: pixels farther (horizontally, from the robot) are left out;
	 * `resolution`: cell size (the map's). */
	NearLabels(double range, double resolution)
	    : m_range(range), m_resolution(resolution)
	{
	}

	/** Adds the labelled pixels of a sweep seen from `pose`. */
	void insert(const LabeledSweep& s, const mrpt::poses::CPose2D& pose);
	/** The label masks over grid `g` (0: no near label). */
	std::vector<float> layer(const GridGeometry& g) const;
	bool empty() const { return m_cells.empty(); }
	double range() const { return m_range; }

private:
	static std::int64_t key(std::int64_t cx, std::int64_t cy)
	{
		return (cx << 32) ^ (cy & 0xffffffffLL);
	}

	double m_range, m_resolution;
	std::unordered_map<std::int64_t, LabelSet::mask_t> m_cells;
};

}  // namespace semnav
