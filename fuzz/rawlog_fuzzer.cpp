/* semnav: semantic navigation from tilting-laser sweeps */
// libFuzzer harness: a rawlog (plain or gzip) through RawlogSweepReader,
// which reads it with RawlogObjectReader. Corrupt data must end in
// RawlogError, never a crash or unbounded memory.
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <semnav/common/Error.h>
#include <semnav/scan/RawlogSweepReader.h>
#include <semnav/scan/RawlogWriter.h>
#include <semnav/scan/TiltGeometry.h>

#include "FuzzFiles.h"

using namespace semnav;

namespace
{
/** A nod of `lines` scan lines of `beams` beams with odometry every 5. */
void writeNods(RawlogWriter& w, int lines, std::size_t beams)
{
	for (int k = 0; k < lines; k++)
	{
		const int tilt = k < lines / 2 ? k : lines - k;
		auto s = mrpt::obs::CObservation2DRangeScan::Create();
		s->sensorLabel = "TILT_LMS";
		s->aperture = static_cast<float>(M_PI);
		s->maxRange = 8.0f;
		s->resizeScan(beams);
		for (std::size_t c = 0; c < beams; c++)
		{
			s->setScanRange(c, 1.0f + 0.01f * tilt + 0.001f * c);
			s->setScanRangeValidity(c, c % 7 != 3);
		}
		s->sensorPose =
		    tiltedSensorPose({0, 0, 0.45}, (-15 + 3.0 * tilt) * M_PI / 180);
		s->timestamp = mrpt::Clock::fromDouble(1.0e9 + 0.03 * k);
		w.write(*s);
		if (k % 5 == 0)
		{
			auto o = mrpt::obs::CObservationOdometry::Create();
			o->sensorLabel = "ODOMETRY";
			o->odometry = mrpt::poses::CPose2D(0.01 * k, 0, 0);
			w.write(*o);
		}
	}
}

void writeSeeds()
{
	if (fuzz::seedDir().empty()) return;
	const auto dir = fuzz::scratchDir("rawlog_seeds");
	for (const bool gz : {false, true})
	{
		const auto path = dir / (gz ? "nods.rawlog.gz" : "nods.rawlog");
		{
			RawlogWriter w(
			    path.string(), 1,
			    gz ? RawlogWriter::Mode::Atomic
			       : RawlogWriter::Mode::Streaming);
			writeNods(w, 24, 31);
			w.commit();
		}
		fuzz::writeSeed(path.filename().string(), fuzz::readBytes(path));
	}
	std::filesystem::remove_all(dir);
}
}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
	writeSeeds();
	return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
	static const auto path = fuzz::scratchDir("rawlog") / "input.rawlog";
	fuzz::writeBytes(path, data, size);
	try
	{
		RawlogSweepReader reader(path.string());
		Sweep s;
		while (reader.next(s))
		{
		}
	}
	catch (const Error&)
	{
	}
	return 0;
}
