/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once
#include <string>

namespace semnav::test
{
/** The source tree (config/, datasets/) and the build tree (apps/), as CMake
 * passes them to every test. */
inline const std::string kSourceDir = SEMNAV_SOURCE_DIR;
inline const std::string kBinaryDir = SEMNAV_BINARY_DIR;
}  // namespace semnav::test
