/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <chrono>

namespace semnav
{
/** Wall-clock milliseconds since `t0` (std::chrono::steady_clock). */
inline double msSince(std::chrono::steady_clock::time_point t0)
{
	return std::chrono::duration<double, std::milli>(
	           std::chrono::steady_clock::now() - t0)
	    .count();
}

}  // namespace semnav
