/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/map/SemanticMap.h>

#include <vector>

#include "MapTestUtils.h"

namespace semnav::test
{
/** A door region (robot frame) in the wall x = 3 facing the robot, centred
 * at (y, z), `width` x `height`, of `pixels` pixels. */
inline LabeledRegion doorPiece(
    int id, double y, double z, double width, double height, std::size_t pixels)
{
	LabeledRegion reg;
	reg.id = id;
	reg.label = Label::Door;
	reg.pixels = pixels;
	reg.imageBox = cv::Rect(0, 0, 1, 1);
	reg.centroid = {3.0, y, z};
	reg.minCorner = {2.98, y - width / 2, z - height / 2};
	reg.maxCorner = {3.02, y + width / 2, z + height / 2};
	reg.width = width;
	reg.height = height;
	reg.meanNormal = {-1, 0, 0};
	return reg;
}

/** The door instances of a map with options `o` after inserting, at the
 * origin, one sweep (floor ahead) per list of regions. */
inline std::vector<ObjectInstance> doorsAfterSweeps(
    const SemanticMap::TOptions& o,
    const std::vector<std::vector<LabeledRegion>>& sweeps)
{
	SemanticMap m(o);
	auto f = makeFakeSweep(floorFan(2.5));
	for (const auto& regions : sweeps)
	{
		f.labeled.regions = regions;
		m.insert(f.sweep, f.labeled, mrpt::poses::CPose2D(0, 0, 0));
	}
	return m.instances(Label::Door);
}
}  // namespace semnav::test
