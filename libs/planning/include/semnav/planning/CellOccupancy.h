/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <cstdint>

namespace semnav
{
/** Occupancy of a grid cell, input of TraversabilityBuilder. */
enum class CellOccupancy : uint8_t
{
	Free = 0,
	Occupied = 1,
	/** Never observed. */
	Unknown = 2
};

}  // namespace semnav
