/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/3rdparty/tclap/CmdLine.h>
#include <mrpt/math/TPose2D.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace semnav
{
class IniSections;

/** Command-line handling shared by the semnav apps, over MRPT's TCLAP.
 *
 * Implements the CLI contract of docs/design.md: `--help` exits 0, bad usage
 * prints one line `<app>: <what>; see --help` and exits 2, and any error
 * thrown by the app's body prints one line `<app>: <what>` and exits 1. */
class CommandLine
{
public:
	CommandLine(std::string appName, const std::string& description);
	~CommandLine();

	/** The TCLAP command line to add arguments to. */
	TCLAP::CmdLine& cmd() { return *m_cmd; }
	const std::string& appName() const { return m_app; }

	/** Parses argv and runs the checks added by addCheck(). Returns nothing
	 * when the app should go on, else the exit code (0 after --help,
	 * --version or --write-config, 2 after bad usage, 1 when the config
	 * cannot be written). */
	std::optional<int> parse(int argc, char** argv);

	/** A usage check run by parse() after parsing: a message makes parse()
	 * report bad usage (exit 2). */
	void addCheck(const std::function<std::optional<std::string>()>& check);

	/** The switch `--json` ("Print a JSON summary on stdout"). */
	TCLAP::SwitchArg& addJson();
	/** `--gt-dir DIR`: semnav-sim's ground truth (`doc` says what for). */
	TCLAP::ValueArg<std::string>& addGtDir(const std::string& doc);
	/** `--config FILE` (default `defaultPath`, "" for built-in values),
	 * loaded by `sections.load()`, and `--write-config FILE` (see
	 * addWriteConfig()). */
	TCLAP::ValueArg<std::string>& addConfig(
	    const IniSections& sections, const std::string& doc,
	    const std::string& defaultPath = "");
	/** `--write-config FILE`: parse() writes the defaults of `sections`
	 * (every section the app reads) to FILE and the app exits 0. */
	void addWriteConfig(const IniSections& sections);

	/** Reports bad usage (one line) and returns exit code 2. */
	int usageError(const std::string& what) const;

	/** Runs the app's body; an exception becomes one line on stderr (the
	 * first line of what(), MRPT's carry backtraces) and exit code 1. */
	int run(const std::function<int()>& body) const;

	/** First non-empty line of a message. */
	static std::string firstLine(const std::string& msg);

	/** Strict parse of an unsigned integer option such as --seed (digits
	 * only, fits 64 bits); nothing when malformed. */
	static std::optional<uint64_t> parseUnsigned(const std::string& s);

	/** Strict parse of a pose option "X,Y,YAW_DEG" (finite numbers; yaw
	 * in degrees, returned in radians); nothing when malformed. */
	static std::optional<mrpt::math::TPose2D> parsePose(const std::string& s);

	/** Strict parse of `count` comma-separated finite numbers ("X,Y,Z");
	 * nothing when malformed. */
	static std::optional<std::vector<double>> parseNumbers(
	    const std::string& s, std::size_t count);

private:
	class OneLineOutput;
	std::optional<int> writeConfig() const;

	std::string m_app;
	std::unique_ptr<OneLineOutput> m_output;
	std::vector<std::unique_ptr<TCLAP::Arg>> m_args;  // outlive m_cmd
	std::unique_ptr<TCLAP::CmdLine> m_cmd;
	std::vector<std::function<std::optional<std::string>()>> m_checks;
	const IniSections* m_writeSections = nullptr;
	TCLAP::ValueArg<std::string>* m_writeConfig = nullptr;
};

}  // namespace semnav
