/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <cstdint>
#include <string>

namespace semnav
{
/** Procedural scene files (docs/generated-scenes.md): an indoor building or
 * an outdoor campus scene with a stop-and-scan trajectory, in the scene
 * format of docs/design.md, built only from its existing labels and
 * primitives.
 *
 * - Indoor: a corridor with 2-3 rooms of varied size on each side, walls
 *   0.08-0.35 m thick, doors 0.8-2.0 m wide (single and double, recessed
 *   or nearly flush), open gaps, washbasins, wastebaskets, stairs,
 *   cabinets, tables with chairs and clutter by the walls.
 * - Outdoor: a curved sidewalk of varying width, grass, buildings with
 *   doors, paths to them, posts, benches, bins (wastebaskets) and low walls.
 *
 * Every trajectory pose is at least TOptions::poseClearance from anything
 * standing on the floor (objects whose bottom is above 1.2 m, such as
 * lintels, do not count) and the straight way between two stops at least
 * TOptions::pathClearance; rooms are entered through open gaps. The text is
 * checked with SceneLoader::parse before it is returned. The same options
 * give the same bytes. */
class SceneGenerator
{
public:
	enum class Kind
	{
		Indoor,
		Outdoor
	};

	struct TOptions
	{
		Kind kind = Kind::Indoor;
		uint64_t seed = 0;
		/** Minimum distance from a pose to any obstacle (m). */
		double poseClearance = 0.45;
		/** Minimum distance from the way between two stops to any obstacle. */
		double pathClearance = 0.30;
	};

	explicit SceneGenerator(const TOptions& opts) : m_opts(opts) {}

	/** The scene file's text (scene name `indoor_<seed>` or
	 * `outdoor_<seed>`). Throws semnav::Error when no layout of the seed
	 * meets the clearances (not seen in practice). */
	std::string generate() const;

	/** "indoor" or "outdoor"; throws semnav::Error naming the known kinds. */
	static Kind kindFromName(const std::string& name);
	static std::string kindName(Kind kind);

private:
	TOptions m_opts;
};

}  // namespace semnav
