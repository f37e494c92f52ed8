/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/CommandLine.h>

#include <iostream>

namespace semnav
{
/** MRPT's TCLAP has no setExceptionHandling(false): parse() reports errors
 * through the output object and returns false. Keep the error as one line
 * instead of TCLAP's multi-line usage dump. */
class CommandLine::OneLineOutput : public TCLAP::StdOutput
{
public:
	void failure(TCLAP::CmdLineInterface&, TCLAP::ArgException& e) override
	{
		failed = true;
		message = e.error();
		std::string id = e.argId();
		if (id.rfind("Argument:", 0) == 0) id = id.substr(9);
		const auto b = id.find_first_not_of(" ()"),
		           l = id.find_last_not_of(" ()");
		id = b == std::string::npos ? "" : id.substr(b, l - b + 1);
		if (!id.empty() && id != "undefined") message += " (" + id + ")";
	}
	bool failed = false;
	std::string message;
};

CommandLine::CommandLine(std::string appName, const std::string& description)
    : m_app(std::move(appName)),
      m_output(std::make_unique<OneLineOutput>()),
      m_cmd(std::make_unique<TCLAP::CmdLine>(description, ' ', "0.1.0"))
{
	m_cmd->setOutput(m_output.get());
}

CommandLine::~CommandLine() = default;

std::optional<int> CommandLine::parse(int argc, char** argv)
{
	if (m_cmd->parse(argc, argv)) return std::nullopt;
	if (!m_output->failed) return 0;  // --help or --version
	return usageError(m_output->message);
}

int CommandLine::usageError(const std::string& what) const
{
	std::cerr << m_app << ": " << what << "; see --help\n";
	return 2;
}

int CommandLine::run(const std::function<int()>& body) const
{
	try
	{
		return body();
	}
	catch (const std::exception& e)
	{
		std::cerr << m_app << ": " << firstLine(e.what()) << "\n";
		return 1;
	}
}

std::optional<uint64_t> CommandLine::parseUnsigned(const std::string& s)
{
	if (s.empty() || s.size() > 19 ||
	    s.find_first_not_of("0123456789") != std::string::npos)
		return std::nullopt;
	return std::stoull(s);
}

std::string CommandLine::firstLine(const std::string& msg)
{
	// The first line with content; MRPT's exceptions open with a
	// "==== MRPT exception ====" banner.
	std::size_t pos = 0;
	while (pos < msg.size())
	{
		std::size_t e = msg.find_first_of("\r\n", pos);
		if (e == std::string::npos) e = msg.size();
		std::string line = msg.substr(pos, e - pos);
		const auto b = line.find_first_not_of(" \t");
		if (b != std::string::npos && line.compare(b, 4, "====") != 0)
			return line.substr(b);
		pos = e + 1;
	}
	return "unknown error";
}

}  // namespace semnav
