/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <cstddef>

namespace semnav
{
/** What the SweepAssembler noticed while building a sweep. */
struct SweepQuality
{
	/** False for a sweep cut short (end of log, stall, robot moved). */
	bool complete = true;
	/** Rows with no scan line (gaps in the tilt sequence), left invalid. */
	std::size_t missingLines = 0;
	/** Lines dropped because they repeated the previous tilt. */
	std::size_t repeatedLines = 0;
	/** True when the head moved up during the sweep. */
	bool ascending = true;
};

}  // namespace semnav
