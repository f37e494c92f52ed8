/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/serialization/CArchive.h>
#include <semnav/common/Error.h>
#include <semnav/scan/RawlogSweepReader.h>

#include <iostream>

namespace semnav
{
RawlogSweepReader::RawlogSweepReader(
    const std::string& path, const SweepAssembler::TOptions& options)
    : m_path(path), m_in(path), m_assembler(options)
{
	// Notes on stderr: MRPT's console output is stdout, which may carry
	// the apps' JSON.
	m_assembler.logging_enable_console_output = false;
	m_assembler.logRegisterCallback(
	    [](std::string_view msg, mrpt::system::VerbosityLevel,
	       std::string_view loggerName, mrpt::Clock::time_point)
	    { std::cerr << loggerName << ": " << msg << std::endl; });
}

RawlogSweepReader::~RawlogSweepReader() = default;

void RawlogSweepReader::push(const mrpt::serialization::CSerializable::Ptr& obj)
{
	if (auto obs = std::dynamic_pointer_cast<mrpt::obs::CObservation>(obj))
	{
		m_lines += IS_CLASS(*obs, mrpt::obs::CObservation2DRangeScan);
		m_assembler.push(obs);
	}
	else if (auto sf = std::dynamic_pointer_cast<mrpt::obs::CSensoryFrame>(obj))
	{
		for (const auto& o : *sf)
		{
			m_lines += o && IS_CLASS(*o, mrpt::obs::CObservation2DRangeScan);
			m_assembler.push(o);
		}
	}
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

void RawlogSweepReader::readMore()
{
	std::string error;
	while (!m_eof && !m_assembler.hasSweep())
	{
		mrpt::serialization::CSerializable::Ptr obj;
		try
		{
			m_eof = !m_in.next(obj);
		}
		catch (const RawlogError& e)
		{
			error = e.what();
			m_eof = true;
		}
		if (!m_eof) push(obj);
	}
	if (!m_eof) return;
	m_assembler.finish();
	// Counted after finish(): the sweep the damage cut short is read too.
	if (!error.empty())
		m_error = error + " (" + std::to_string(m_assembler.sweepsEmitted()) +
		          " sweeps read)";
}

std::string RawlogSweepReader::noSweepsMessage() const
{
	return "no sweeps in " + m_path + " (" +
	       std::to_string(m_in.objectsRead()) + " objects, " +
	       std::to_string(m_lines) + " scan lines)";
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
	if (out.empty()) throw RawlogError(reader.noSweepsMessage());
	return out;
}

}  // namespace semnav
