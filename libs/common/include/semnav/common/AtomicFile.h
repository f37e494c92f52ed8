/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <functional>
#include <string>

namespace semnav
{
/** Writes `path` atomically: `write` fills a temporary file next to `path`
 * (same directory, so rename is atomic); on success the temporary is renamed
 * over `path`, on any exception it is removed and the exception rethrown.
 * A reader never sees a half-written file and an old file is never lost. */
void writeAtomically(
    const std::string& path,
    const std::function<void(const std::string& tmpPath)>& write);

/** writeAtomically() for a text or binary blob. */
void writeFileAtomically(const std::string& path, const std::string& content);

/** Creates a directory and its parents; throws IoError on failure. */
void createDirectories(const std::string& path);

}  // namespace semnav
