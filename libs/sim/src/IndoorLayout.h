/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once
// Indoor building of SceneGenerator (src/ only).

#include "SceneDraft.h"

namespace semnav::detail
{
/** A corridor along x with 2-3 rooms on each side. Each room opens onto the
 * corridor through a closed door, a closed double door or an open gap;
 * some rooms also share a closed door, and the corridor may end in one.
 * Rooms hold washbasins, wastebaskets, cabinets, a table with chairs and
 * clutter by the walls; one room may hold stairs. The trajectory walks the
 * corridor and turns into the rooms with open gaps. */
class IndoorLayout
{
public:
	/** Fills `draft`. */
	static void build(SceneDraft& draft);
};

}  // namespace semnav::detail
