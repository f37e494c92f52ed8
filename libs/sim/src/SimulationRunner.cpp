/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/math/wrap2pi.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <semnav/common/AtomicFile.h>
#include <semnav/common/DatasetCompletion.h>
#include <semnav/common/Error.h>
#include <semnav/common/StagedDirectory.h>
#include <semnav/scan/RawlogWriter.h>
#include <semnav/sim/OdometrySimulator.h>
#include <semnav/sim/RayCaster.h>
#include <semnav/sim/SimulationRunner.h>
#include <semnav/sim/TiltingLaserSimulator.h>

#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

namespace semnav
{
namespace
{
/** 2020-01-01T00:00:00Z in seconds since 1970. */
constexpr int64_t kEpochUnix = 1577836800;
constexpr double kTicksPerSecond =
    static_cast<double>(mrpt::Clock::period::den) / mrpt::Clock::period::num;

int64_t toTicks(double seconds)
{
	return static_cast<int64_t>(std::llround(seconds * kTicksPerSecond));
}

/** Seconds since 1970 with 6 decimals, exact from integer ticks. */
std::string unixTime(int64_t ticksSinceEpoch)
{
	const int64_t ticksPerUs = static_cast<int64_t>(kTicksPerSecond / 1e6);
	const int64_t us = (ticksSinceEpoch + ticksPerUs / 2) / ticksPerUs;
	char buf[64];
	std::snprintf(
	    buf, sizeof(buf), "%" PRId64 ".%06" PRId64, kEpochUnix + us / 1000000,
	    us % 1000000);
	return buf;
}

bool isLabelImage(const std::string& name)
{
	return name.rfind("sweep_", 0) == 0 && name.size() > 4 &&
	       name.compare(name.size() - 4, 4, ".png") == 0;
}

/** Pixels of each object id (the label image's high byte) in one sweep. */
std::vector<std::size_t> countObjectPixels(
    const cv::Mat& labels, const Scene& scene)
{
	std::vector<std::size_t> count(scene.objects.size() + 1, 0);
	for (int r = 0; r < labels.rows; r++)
		for (int c = 0; c < labels.cols; c++)
		{
			const std::size_t id = labels.at<uint16_t>(r, c) >> 8;
			if (id < count.size()) count[id]++;
		}
	return count;
}

std::string joinPath(const std::string& dir, const std::string& name)
{
	if (dir.empty()) return name;
	return dir.back() == '/' ? dir + name : dir + "/" + name;
}
}  // namespace

mrpt::Clock::time_point SimulationRunner::epoch()
{
	return mrpt::Clock::fromDouble(static_cast<double>(kEpochUnix));
}

SimulationRunner::SimulationRunner(
    const Scene& scene, const TOptions& options, uint64_t seed)
    : m_scene(scene), m_options(options), m_seed(seed)
{
	if (m_scene.name.empty() || m_scene.name == "." || m_scene.name == ".." ||
	    m_scene.name.find('/') != std::string::npos)
		throw SceneError(
		    "scene name '" + m_scene.name + "' cannot be used as a file name");
	if (m_scene.trajectory.empty())
		throw SceneError(
		    "scene '" + m_scene.name + "' has an empty trajectory");
}

SimulationResult SimulationRunner::run(
    const std::string& outDir, const ProgressCallback& progress) const
{
	const Scene& sc = m_scene;
	SimulationResult res;
	res.rawlogPath = joinPath(outDir, sc.name + ".rawlog");
	res.gtPath = joinPath(outDir, sc.name + ".gt.txt");
	res.labelsDir = joinPath(outDir, sc.name + ".labels");
	createDirectories(outDir);
	// Everything is written beside the dataset first (the label images to a
	// directory swapped in as a whole); from the first file replaced to the
	// last the marker says the dataset is incomplete.
	StagedDirectory::checkReplaceable(res.labelsDir, isLabelImage);
	StagedDirectory labels(res.labelsDir, isLabelImage);

	RayCaster caster(sc, m_seed, m_options.terrainCell);
	caster.setMode(
	    m_options.bruteForce ? RayCaster::Mode::BruteForce
	                         : RayCaster::Mode::Accelerated);
	TiltingLaserSimulator laser(
	    caster, sc.sensor, m_seed, m_options.sensorLabel);
	laser.setThreads(m_options.threads);
	const auto odo =
	    OdometrySimulator::simulate(sc.odometry, sc.trajectory, m_seed);

	const mrpt::Clock::time_point t0 = epoch();
	const std::size_t n = sc.trajectory.size();
	std::ostringstream gt;
	gt << "# index timestamp x y yaw_rad (true robot pose; timestamp = first "
	      "line of "
	      "the sweep)\n";

	RawlogWriter rawlog(res.rawlogPath, m_options.compressLevel);
	int64_t ticks = 0;  // since epoch()
	for (std::size_t i = 0; i < n; i++)
	{
		const auto& pose = sc.trajectory[i];
		if (i > 0)
		{
			const auto& prev = sc.trajectory[i - 1];
			const double dist = std::hypot(pose.x - prev.x, pose.y - prev.y);
			const double turn =
			    std::abs(std::remainder(pose.phi - prev.phi, 2 * M_PI));
			ticks += toTicks(
			    dist / m_options.robotSpeed + turn / m_options.robotTurnRate);
		}
		const mrpt::Clock::time_point ts = t0 + mrpt::Clock::duration(ticks);

		mrpt::obs::CObservationOdometry o;
		o.sensorLabel = "ODOMETRY";
		o.timestamp = ts;
		o.odometry = odo[i];
		rawlog.write(o);
		res.odometry++;

		const SimulatedSweep sw =
		    laser.simulate(pose, i, ts, m_options.linePeriod);
		for (const auto& line : sw.lines) rawlog.write(line);
		res.scans += sw.lines.size();

		res.objectPixels.push_back(countObjectPixels(sw.labels, sc));
		std::vector<uchar> png;
		if (!cv::imencode(".png", sw.labels, png))
			throw IoError(
			    "cannot encode the label image of sweep " + std::to_string(i));
		char name[32];
		std::snprintf(name, sizeof(name), "sweep_%04zu.png", i);
		writeFileAtomically(
		    joinPath(labels.path(), name), std::string(png.begin(), png.end()));

		char line[160];
		std::snprintf(
		    line, sizeof(line), "%zu %s %.6f %.6f %.9f\n", i,
		    unixTime(ticks).c_str(), pose.x, pose.y,
		    mrpt::math::wrapToPi(pose.phi));
		gt << line;

		ticks += toTicks(laser.lineCount() * m_options.linePeriod);
		res.sweeps++;
		if (progress) progress(i + 1, n);
	}
	DatasetCompletion::begin(outDir, sc.name);
	rawlog.commit();
	writeFileAtomically(res.gtPath, gt.str());
	labels.commit();
	DatasetCompletion::end(outDir, sc.name);
	return res;
}

}  // namespace semnav
