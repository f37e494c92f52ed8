/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/core/Clock.h>
#include <semnav/sim/Scene.h>
#include <semnav/sim/SimulatorOptions.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace semnav
{
/** What SimulationRunner::run() wrote. */
struct SimulationResult
{
	std::string rawlogPath;    ///< <out>/<name>.rawlog
	std::string gtPath;        ///< <out>/<name>.gt.txt
	std::string labelsDir;     ///< <out>/<name>.labels
	std::size_t sweeps = 0;    ///< sweeps (= trajectory poses)
	std::size_t scans = 0;     ///< CObservation2DRangeScan lines in the rawlog
	std::size_t odometry = 0;  ///< CObservationOdometry entries in the rawlog
	/** Ground-truth pixels per sweep and object: objectPixels[sweep][id],
	 * id as in the label images (0: no object, e.g. floor). */
	std::vector<std::vector<std::size_t>> objectPixels;
};

/** Simulates a whole scene, stop-and-scan, and writes the rawlog and the
 * ground truth of docs/design.md.
 *
 * For each trajectory pose i: a CObservationOdometry (sensorLabel
 * "ODOMETRY", noisy odometry from OdometrySimulator) then the lineCount scan
 * lines of sweep i (TiltingLaserSimulator; even sweeps ascend, odd ones
 * descend). Simulated time starts at epoch() (2020-01-01T00:00:00Z); the
 * odometry entry and the first line of sweep i share one timestamp; lines
 * are linePeriod apart; a sweep lasts lineCount * linePeriod, then the robot
 * travels for distance / robotSpeed + |heading change| / robotTurnRate.
 *
 * Files (written beside the dataset, then each swapped in atomically, the
 * labels directory as a whole; from the first swap to the last
 * `<out>/<name>.incomplete` marks the dataset incomplete, see
 * DatasetCompletion): `<out>/<name>.rawlog`, `<out>/<name>.gt.txt` (a `#`
 * header line, then per sweep `index timestamp x y yaw_rad` with the timestamp
 * of its first line in seconds since 1970, 6 decimals, and the true pose) and
 * `<out>/<name>.labels/sweep_NNNN.png` (16-bit, SimulatedSweep::labels).
 * Seeds: terrain, range noise and odometry noise all derive from `seed`. */
class SimulationRunner
{
public:
	using TOptions = SimulatorOptions;
	/** Called after each sweep with (sweeps done, total sweeps). */
	using ProgressCallback = std::function<void(std::size_t, std::size_t)>;

	/** Throws SceneError when the scene has no name (or a name that is not a
	 * plain file name) or an empty trajectory. */
	SimulationRunner(
	    const Scene& scene, const TOptions& options, uint64_t seed = 0);

	/** Runs the simulation, creating `outDir` if needed; throws Error
	 * subclasses (IoError for files). */
	SimulationResult run(
	    const std::string& outDir, const ProgressCallback& progress = {}) const;

	/** Start of simulated time: 2020-01-01T00:00:00Z. */
	static mrpt::Clock::time_point epoch();

	const TOptions& options() const { return m_options; }

private:
	Scene m_scene;
	TOptions m_options;
	uint64_t m_seed;
};

}  // namespace semnav
