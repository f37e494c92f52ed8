/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once
// Outdoor scene of SceneGenerator (src/ only).

#include "SceneDraft.h"

namespace semnav::detail
{
/** A curved sidewalk of varying width across the scene, grass around it,
 * one or two buildings along the north edge with doors (single or double,
 * recessed or nearly flush), straight paths from the sidewalk to some
 * doors, and posts, benches, bins (wastebaskets) and low walls by the
 * paths. The trajectory follows the sidewalk and walks up the paths toward
 * the doors. */
class OutdoorLayout
{
public:
	/** Fills `draft`. */
	static void build(SceneDraft& draft);
};

}  // namespace semnav::detail
