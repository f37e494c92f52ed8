/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/sim/Scene.h>

#include <string>

namespace semnav
{
/** Reads scene files (docs/design.md "Scene" format).
 *
 * Every error throws SceneError with a one-line message naming the file,
 * the line (when the YAML parser knows it) and the key path, e.g.
 * `office.yaml:12: objects[3].box.size: expected 3 numbers, got 2`.
 * Unknown keys, missing required keys and bad values (negative sizes,
 * unknown labels, polygons with < 3 vertices, ...) are errors. */
class SceneLoader
{
public:
	/** Loads a scene file; throws SceneError (also for a missing file). */
	static Scene loadFile(const std::string& path);
	/** Parses YAML text; `sourceName` prefixes error messages. */
	static Scene parse(
	    const std::string& yamlText, const std::string& sourceName);
};

}  // namespace semnav
