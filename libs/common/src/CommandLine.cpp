/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/CommandLine.h>
#include <semnav/common/IniSections.h>
#include <semnav/common/Printable.h>

#include <cmath>
#include <iostream>
#include <sstream>

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
	if (!m_cmd->parse(argc, argv))
	{
		if (!m_output->failed) return 0;  // --help or --version
		return usageError(m_output->message);
	}
	if (const auto code = writeConfig()) return code;
	for (const auto& check : m_checks)
		if (const auto problem = check()) return usageError(*problem);
	return std::nullopt;
}

void CommandLine::addCheck(
    const std::function<std::optional<std::string>()>& check)
{
	m_checks.push_back(check);
}

TCLAP::SwitchArg& CommandLine::addJson()
{
	auto a = std::make_unique<TCLAP::SwitchArg>(
	    "", "json", "Print a JSON summary on stdout", *m_cmd, false);
	auto& ref = *a;
	m_args.push_back(std::move(a));
	return ref;
}

TCLAP::ValueArg<std::string>& CommandLine::addGtDir(const std::string& doc)
{
	auto a = std::make_unique<TCLAP::ValueArg<std::string>>(
	    "", "gt-dir",
	    "Ground truth written by semnav-sim (the directory holding "
	    "<name>.gt.txt and <name>.labels/): " +
	        doc,
	    false, "", "DIR", *m_cmd);
	auto& ref = *a;
	m_args.push_back(std::move(a));
	return ref;
}

TCLAP::ValueArg<std::string>& CommandLine::addConfig(
    const IniSections& sections, const std::string& doc,
    const std::string& defaultPath)
{
	std::string text = doc + " (sections:";
	for (const auto& s : sections.sections()) text += " [" + s + "]";
	text += defaultPath.empty() ? "); default: built-in values"
	                            : "); default: " + defaultPath;
	auto a = std::make_unique<TCLAP::ValueArg<std::string>>(
	    "", "config", text, false, defaultPath, "C.ini", *m_cmd);
	auto& ref = *a;
	m_args.push_back(std::move(a));
	addWriteConfig(sections);
	return ref;
}

void CommandLine::addWriteConfig(const IniSections& sections)
{
	m_writeSections = &sections;
	if (m_writeConfig) return;
	auto a = std::make_unique<TCLAP::ValueArg<std::string>>(
	    "", "write-config",
	    "Write the built-in defaults of every INI section this app reads to "
	    "FILE and exit",
	    false, "", "FILE", *m_cmd);
	m_writeConfig = a.get();
	m_args.push_back(std::move(a));
}

std::optional<int> CommandLine::writeConfig() const
{
	if (!m_writeConfig || m_writeConfig->getValue().empty())
		return std::nullopt;
	return run(
	    [&]
	    {
		    m_writeSections->write(m_writeConfig->getValue());
		    return 0;
	    });
}

int CommandLine::usageError(const std::string& what) const
{
	std::cerr << m_app << ": " << printable(what) << "; see --help\n";
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
		std::cerr << m_app << ": " << printable(firstLine(e.what())) << "\n";
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

std::optional<std::vector<double>> CommandLine::parseNumbers(
    const std::string& s, std::size_t count)
{
	std::stringstream ss(s);
	std::vector<double> v;
	for (std::string t; std::getline(ss, t, ',');)
	{
		try
		{
			std::size_t n = 0;
			v.push_back(std::stod(t, &n));
			if (n != t.size() || !std::isfinite(v.back())) return std::nullopt;
		}
		catch (const std::exception&)
		{
			return std::nullopt;
		}
	}
	if (v.size() != count) return std::nullopt;
	return v;
}

std::optional<mrpt::math::TPose2D> CommandLine::parsePose(const std::string& s)
{
	const auto v = parseNumbers(s, 3);
	if (!v) return std::nullopt;
	return mrpt::math::TPose2D((*v)[0], (*v)[1], (*v)[2] * M_PI / 180);
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
