/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace semnav
{
/** Semantic labels. The numeric value is the label id stored in label
 * images (low byte) and the bit index in a LabelSet. Order is part of the
 * file-format contract (docs/design.md): never reorder, only append. The
 * named values are the built-in classes; classes added to the
 * ClassRegistry at run time take the next ids (a Label is any registered
 * id). */
enum class Label : uint8_t
{
	Unknown = 0,
	Floor,
	Ceiling,
	Wall,
	Door,
	Sidewalk,
	Grass,
	Stairs,
	Washbasin,
	Wastebasket,
	Obstacle
};

/** Number of built-in labels (Unknown included). */
constexpr std::size_t kBuiltInLabelCount = 11;

/** Most classes the ClassRegistry holds (ids 0..23): a LabelSet is kept in a
 * float map layer, which holds integers up to 2^24 exactly. Size per-label
 * tables by this or by ClassRegistry::size(). */
constexpr std::size_t kMaxLabelCount = 24;

/** All registered labels in id order (ClassRegistry::labels()). */
const std::vector<Label>& allLabels();

/** Lower-case name as used in files and commands, e.g. "wastebasket";
 * "unknown" for an id that is not registered. */
const std::string& labelName(Label l);

/** Parses a lower-case name; throws UnknownLabelError listing the known
 * names. */
Label labelFromName(const std::string& name);

/** Label from its numeric id; throws UnknownLabelError when no class has
 * it. */
Label labelFromId(unsigned id);

/** Comma-separated list of all label names, for messages. */
std::string knownLabelNames();

}  // namespace semnav
