/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/3rdparty/tclap/CmdLine.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

namespace semnav
{
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

	/** Parses argv. Returns nothing when the app should go on, else the
	 * exit code (0 after --help/--version, 2 after bad usage). */
	std::optional<int> parse(int argc, char** argv);

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

private:
	class OneLineOutput;
	std::string m_app;
	std::unique_ptr<OneLineOutput> m_output;
	std::unique_ptr<TCLAP::CmdLine> m_cmd;
};

}  // namespace semnav
