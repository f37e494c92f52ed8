/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CLoadableOptions.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace semnav::test
{
/** A section of a shipped file and the options struct it holds. */
struct ShippedSection
{
	std::string name;
	std::function<std::unique_ptr<mrpt::config::CLoadableOptions>()> make;
};

/** What a file in config/ must hold: the code's defaults of its sections,
 * its deliberate overrides, and text that is not semnav's options. */
struct ShippedConfig
{
	/** File name in config/. */
	std::string file;
	/** Comment at the top (without "# "). */
	std::string header;
	std::vector<ShippedSection> sections;
	/** The deliberate overrides, as INI text loaded into the sections'
	 * structs before they are written (each with its reason). */
	std::string overrides;
	/** INI text written as given after a section's "[name]" line: keys
	 * of other programs (rawlog-grabber's sensor keys). Section name ->
	 * text. */
	std::vector<std::pair<std::string, std::string>> foreignKeys;
	/** INI text written as given before the sections (rawlog-grabber's
	 * [global]) ... */
	std::string foreignBefore;
	/** ... and after them (sections that change another for one class). */
	std::string foreignAfter;
	/** The file's own text from the line starting with this on is kept as
	 * written (MRPT's navigator sections); empty: none. */
	std::string keptTailMarker;
};

/** Every file shipped in config/. */
std::vector<ShippedConfig> shippedConfigs();

/** The text `spec` gives: defaults + overrides, written as
 * writeConfigFile() does, with the foreign text; `current` is the file's
 * present text (for the kept tail). */
std::string expectedText(const ShippedConfig& spec, const std::string& current);

}  // namespace semnav::test
