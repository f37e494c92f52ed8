/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt/system/filesystem.h>
#include <semnav/common/CommandLine.h>
#include <semnav/common/Error.h>
#include <semnav/scan/RawlogSweepReader.h>

#include <iostream>

namespace semnav
{
RawlogSweepReader::RawlogSweepReader(
    const std::string& path, const SweepAssembler::TOptions& options)
    : m_path(path), m_assembler(options)
{
	// Notes on stderr: MRPT's console output is stdout, which may carry
	// the apps' JSON.
	m_assembler.logging_enable_console_output = false;
	m_assembler.logRegisterCallback(
	    [](std::string_view msg, mrpt::system::VerbosityLevel,
	       std::string_view loggerName, mrpt::Clock::time_point)
	    { std::cerr << loggerName << ": " << msg << std::endl; });
	if (!mrpt::system::fileExists(path))
		throw RawlogError("cannot open rawlog " + path + ": no such file");
	m_in = std::make_unique<mrpt::io::CFileGZInputStream>();
	std::string err;
	if (!m_in->open(path, err))
		throw RawlogError("cannot open rawlog " + path + ": " + err);
}

RawlogSweepReader::~RawlogSweepReader() = default;

void RawlogSweepReader::readMore()
{
	auto arch = mrpt::serialization::archiveFrom(*m_in);
	while (!m_eof && !m_assembler.hasSweep())
	{
		mrpt::serialization::CSerializable::Ptr obj;
		try
		{
			obj = arch.ReadObject();
		}
		catch (const mrpt::serialization::CExceptionEOF&)
		{
			m_eof = true;
			break;
		}
		catch (const std::exception& e)
		{
			const std::string what = CommandLine::firstLine(e.what());
			m_error = "rawlog " + m_path + " is corrupt or truncated after " +
			          std::to_string(m_objects) + " objects (" +
			          std::to_string(m_assembler.sweepsEmitted()) +
			          " sweeps read): " + what;
			m_eof = true;
			break;
		}
		m_objects++;
		if (auto obs = std::dynamic_pointer_cast<mrpt::obs::CObservation>(obj))
			m_assembler.push(obs);
		else if (
		    auto sf = std::dynamic_pointer_cast<mrpt::obs::CSensoryFrame>(obj))
			for (const auto& o : *sf) m_assembler.push(o);
		else if (
		    auto acts =
		        std::dynamic_pointer_cast<mrpt::obs::CActionCollection>(obj))
		{
			if (auto mv = acts->getBestMovementEstimation())
			{
				m_actionOdometry =
				    m_actionOdometry + mv->rawOdometryIncrementReading;
				m_assembler.pushOdometry(m_actionOdometry);
			}
		}
	}
	if (m_eof) m_assembler.finish();
}

bool RawlogSweepReader::next(Sweep& out)
{
	if (!m_assembler.hasSweep() && !m_eof) readMore();
	if (m_assembler.hasSweep())
	{
		out = m_assembler.pop();
		return true;
	}
	if (!m_error.empty())
	{
		const std::string e = m_error;
		m_error.clear();
		throw RawlogError(e);
	}
	return false;
}

std::vector<Sweep> readRawlogSweeps(
    const std::string& path, const SweepAssembler::TOptions& options)
{
	RawlogSweepReader reader(path, options);
	std::vector<Sweep> out;
	Sweep s;
	while (reader.next(s)) out.push_back(std::move(s));
	return out;
}

}  // namespace semnav
