/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <array>
#include <cstdint>
#include <string>

namespace semnav
{
/** Semantic labels. The numeric value is the label id stored in label
 * images (low byte) and the bit index in a LabelSet. Order is part of the
 * file-format contract (docs/design.md): never reorder, only append. */
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

/** Number of labels (Unknown included). */
constexpr std::size_t kLabelCount = 11;

/** All labels in id order. */
const std::array<Label, kLabelCount>& allLabels();

/** Lower-case name as used in files and commands, e.g. "wastebasket". */
const std::string& labelName(Label l);

/** Parses a lower-case name; throws UnknownLabelError listing the known
 * names. */
Label labelFromName(const std::string& name);

/** Label from its numeric id; throws UnknownLabelError when out of range. */
Label labelFromId(unsigned id);

/** Comma-separated list of all label names, for messages. */
std::string knownLabelNames();

}  // namespace semnav
