/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <semnav/scan/RawlogWriter.h>
#include <semnav/scan/TiltGeometry.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>

namespace semnav::test
{
/** An empty directory semnav_<name>_<pid> under the temp directory. */
inline std::filesystem::path tempDir(const std::string& name)
{
	const auto d = std::filesystem::temp_directory_path() /
	               ("semnav_" + name + "_" + std::to_string(::getpid()));
	std::filesystem::remove_all(d);
	std::filesystem::create_directories(d);
	return d;
}

/** Range of beam `c` on a synthetic line at tilt index `k`: unique per pixel
 * so tests can check where every value went. */
inline float syntheticRange(int k, std::size_t c)
{
	return 1.0f + 0.01f * k + 0.001f * c;
}

/** A 2D scan line at tilt index k (theta = thetaMin + k * step). */
inline mrpt::obs::CObservation2DRangeScan::Ptr makeLine(
    int k, double thetaMin = -15 * M_PI / 180, double step = 0.5 * M_PI / 180,
    std::size_t beams = 361, const std::string& label = "TILT_LMS")
{
	auto s = mrpt::obs::CObservation2DRangeScan::Create();
	s->sensorLabel = label;
	s->aperture = static_cast<float>(M_PI);
	s->rightToLeft = true;
	s->maxRange = 8.0f;
	s->resizeScan(beams);
	for (std::size_t c = 0; c < beams; c++)
	{
		s->setScanRange(c, syntheticRange(k, c));
		s->setScanRangeValidity(c, (c % 50) != 7);
	}
	s->sensorPose = tiltedSensorPose({0, 0, 0.45}, thetaMin + k * step);
	s->timestamp = mrpt::Clock::fromDouble(1.0e9 + 0.03 * k);
	return s;
}

inline mrpt::obs::CObservationOdometry::Ptr makeOdometry(
    double x, double y, double yaw)
{
	auto o = mrpt::obs::CObservationOdometry::Create();
	o->sensorLabel = "ODOMETRY";
	o->odometry = mrpt::poses::CPose2D(x, y, yaw);
	return o;
}

/** A robot's streamed recording: scan lines of a nodding head with an
 * odometry reading every 5 lines, the robot at `x` (moving `dx` per
 * reading while `driving`). */
class LiveRecording
{
public:
	explicit LiveRecording(const std::string& path)
	    : m_writer(path, 1, RawlogWriter::Mode::Streaming)
	{
		m_writer.write(*makeOdometry(0, 0, 0));
	}
	/** One nod from tilt index `from` to `to` (inclusive), skipping the
	 * lines in [skipFrom, skipTo]. */
	void nod(int from, int to, int skipFrom = -1, int skipTo = -2)
	{
		const int dir = to >= from ? 1 : -1;
		for (int k = from;; k += dir)
		{
			if (k < skipFrom || k > skipTo) m_writer.write(*makeLine(k));
			if (++m_lines % 5 == 0)
			{
				if (driving) x += dx;
				m_writer.write(*makeOdometry(x, 0, 0));
			}
			if (k == to) break;
		}
	}
	void commit() { m_writer.commit(); }

	bool driving = false;
	double x = 0, dx = 0.002;  // a slow drive: 2 mm per reading

private:
	RawlogWriter m_writer;
	int m_lines = 0;
};

/** Writes the recording of a stop-and-scan run: 3 sweeps taken standing
 * (the second with 21 lines lost) and the nods of two drives, ending while
 * driving. Returns where the robot stopped. */
inline double writeStopAndScanRecording(const std::string& path)
{
	LiveRecording rec(path);
	rec.nod(0, 210);          // standing
	rec.nod(210, 0, 60, 80);  // standing, 21 lines lost
	rec.driving = true;       // the head keeps nodding while the robot drives
	rec.nod(0, 210);
	rec.nod(210, 0);
	rec.nod(0, 100);
	rec.driving = false;  // stops mid-nod: the rest of this nod is partial
	rec.nod(101, 210);
	const double stoppedAt = rec.x;
	rec.nod(210, 0);  // standing
	rec.driving = true;
	rec.nod(0, 210);
	rec.commit();
	return stoppedAt;
}

}  // namespace semnav::test
