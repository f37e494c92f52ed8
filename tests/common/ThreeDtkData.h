/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <gtest/gtest.h>

#include <filesystem>

namespace semnav::test
{
/** Where the real 3DTK scans live, outside the repo (see
 * ../shared/data/3dtk/README.md). */
inline const std::filesystem::path kThreeDtkDir =
    std::filesystem::path(SEMNAV_SOURCE_DIR) / ".." / "shared" / "data" /
    "3dtk";
}  // namespace semnav::test

/** Skips the test with a clear message when `file` of the 3DTK data is
 * absent. */
#define SKIP_WITHOUT_3DTK(file)                                        \
	if (!std::filesystem::exists(semnav::test::kThreeDtkDir / (file))) \
	GTEST_SKIP() << "3DTK data not found at "                          \
	             << (semnav::test::kThreeDtkDir / (file)).string()     \
	             << " (real-scan checks skipped)"
