/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/math/TPose2D.h>
#include <semnav/scan/SweepAssembler.h>

#include <cstddef>
#include <string>
#include <vector>

namespace semnav
{
class SceneLineCaster;

/** What checkCapture() found in a captured rawlog. */
struct CaptureCheckResult
{
	std::size_t objects = 0;  ///< objects read
	std::size_t lines = 0;    ///< CObservation2DRangeScan among them
	std::size_t sweepsComplete = 0, sweepsIncomplete = 0;
	/** The file is cut short (e.g. writer killed) or corrupt from some
	 * object on: what comes before it was read. */
	bool truncated = false;
	std::string truncation;  ///< the reader's line: file, object, byte
	/** Over the valid pixels of all sweeps. */
	std::size_t pixels = 0;
	/** Median |captured - true| (m). */
	double medianAbsError = 0;
	/** Fraction of pixels within 3 sigma of the truth cast at the row's
	 * tilt, and within 3 sigma of the truth at some tilt within
	 * +-tiltTolerance (the head reports whole motor steps). */
	double within3Sigma = 0, within3SigmaTilt = 0;
	/** Pixels valid in the capture where the scene has no return within
	 * range, and the reverse. */
	std::size_t spurious = 0, missed = 0;
	/** Per sweep: rows, lowest and highest tilt (rad), complete. */
	struct SweepInfo
	{
		std::size_t rows = 0, cols = 0, missingLines = 0, pixels = 0;
		/** As within3SigmaTilt, over this sweep. */
		double within3SigmaTilt = 0;
		double thetaMin = 0, thetaMax = 0;
		bool complete = false;
	};
	std::vector<SweepInfo> sweeps;
};

/** Tilt of the captured lines against the emulator's truth log. */
struct TiltCheckResult
{
	std::size_t matched = 0;  ///< lines with a scan within 5 ms
	double medianAbsErrorDeg = 0, p95AbsErrorDeg = 0;
	/** Median (line time - scan time), ms. */
	double medianTimeOffsetMs = 0;
};

/** Matches each scan line of `rawlogPath` with the scan of LmsEmulator's
 * truth log (Options::truthLog) nearest in time and compares tilts. */
TiltCheckResult checkTilts(
    const std::string& rawlogPath, const std::string& truthLogPath);

/** Reads a rawlog written by rawlog-grabber with CTiltingLMS2xx, assembles
 * its sweeps (SweepAssembler, default options) and compares every sweep
 * with the scene ray-cast from `robotPose` at each row's own tilt.
 * A sweep is complete when it spans 95 % of `nominalSpan` (rad).
 * A truncated file is not an error here: what could be read is checked
 * and `truncated` says where it ends (semnav-device-emulator --check then
 * exits 1 unless --truncated-ok). Throws
 * RawlogError when the file cannot be opened or holds no scan line. */
CaptureCheckResult checkCapture(
    const std::string& rawlogPath, const SceneLineCaster& caster,
    const mrpt::math::TPose2D& robotPose, double rangeNoise,
    double tiltTolerance, double nominalSpan);

}  // namespace semnav
