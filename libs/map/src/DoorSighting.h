/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/math/TPoint3D.h>

namespace semnav
{
class LabeledSweep;
struct LabeledRegion;

/** The middle, along its wall, of a vertical region's columns that span at
 * least `share` of the region's height (robot frame; height: the points'
 * mean). A door leaf fills its opening from bottom to top, so these columns
 * are the door; a strip of wall or frame beside it that the region took in
 * is lower. share <= 0, a region without a horizontal normal or without
 * points: the middle of the region's bounding box. */
mrpt::math::TPoint3D doorRegionMiddle(
    const LabeledSweep& ls, const LabeledRegion& reg, double share);

}  // namespace semnav
