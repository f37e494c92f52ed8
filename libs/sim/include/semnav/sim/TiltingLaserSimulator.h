/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/core/Clock.h>
#include <mrpt/math/TPose2D.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <semnav/scan/Sweep.h>
#include <semnav/sim/RayCaster.h>
#include <semnav/sim/Scene.h>

#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

namespace semnav
{
/** One simulated sweep of the tilting LMS200. */
struct SimulatedSweep
{
	/** Scan lines in acquisition order (ascending tilt for even sweep
	 * indices, descending for odd ones). */
	std::vector<mrpt::obs::CObservation2DRangeScan> lines;
	/** Ground-truth labels, CV_16UC1, rows = lines by increasing tilt
	 * (row 0 = lowest, whatever the nodding direction), cols = beams
	 * (col 0 = phiMin). Pixel = label id | instance id << 8; 0 where the
	 * beam has no valid return. */
	cv::Mat labels;
	/** Noise-free ranges, CV_32FC1, same layout as `labels`; 0 where the
	 * beam has no valid return. */
	cv::Mat trueRanges;
	/** Tilt of each label-image row (increasing). */
	std::vector<double> thetas;
	/** Bearing of each column relative to the scanner's x axis
	 * (phi_c - phiCenter), as MRPT and Sweep::phi() see them. */
	std::vector<double> bearings;
	bool ascending = true;
	std::size_t index = 0;
	/** True robot pose (world frame). */
	mrpt::math::TPose2D truePose;

	/** The lines as an organized Sweep (row 0 = lowest tilt, phi(c) =
	 * bearings[c], timestamp = first line's); its odometry is left unset. */
	Sweep toSweep() const;
};

/** Ray-casting model of a SICK LMS200 on a nodding head (stop-and-scan).
 *
 * Line r of an ascending sweep has tilt theta_r = thetaMin + r thetaStep
 * (r = 0 .. lineCount-1, both ends included) and sensorPose
 * tiltedSensorPose(mount, theta_r, phiCenter) in the robot frame. Beam c
 * has bearing phi_c = phiMin + c phiStep; its direction in the scanner frame
 * is (cos(phi_c - phiCenter), sin(phi_c - phiCenter), 0), with
 * phiCenter = phiMin + (beamCount-1) phiStep / 2, which is MRPT's own beam
 * layout for aperture = (beamCount-1) phiStep and rightToLeft = true
 * (= phiMax - phiMin when the step divides the field of view).
 *
 * Measured range = true range + N(0, rangeNoise). No return, or a measured
 * range > maxRange or <= 0, gives an invalid beam whose stored range is
 * maxRange. The noise of line r of sweep k comes from its own generator
 * seeded from (seed, k, r), so results do not depend on the thread count. */
class TiltingLaserSimulator
{
public:
	/** `caster` must outlive the simulator. Throws Error if the spec has
	 * no beams or lines, or an instance id does not fit in the label
	 * image's high byte (> 255). */
	TiltingLaserSimulator(
	    const RayCaster& caster, const SensorSpec& spec, uint64_t seed = 0,
	    std::string sensorLabel = "TILT_LMS");

	/** Simulates sweep `sweepIndex` from the true robot pose; line i
	 * (acquisition order) is stamped t0 + i * linePeriod seconds. */
	SimulatedSweep simulate(
	    const mrpt::math::TPose2D& robotPose, std::size_t sweepIndex,
	    mrpt::Clock::time_point t0, double linePeriod) const;

	/** OpenMP threads over scan lines; 0 = all available (default). */
	void setThreads(int n) { m_threads = n; }
	int threads() const { return m_threads; }

	std::size_t lineCount() const { return m_thetas.size(); }
	std::size_t beamCount() const { return m_phis.size(); }
	/** Tilts by increasing value (row order of the label image). */
	const std::vector<double>& thetas() const { return m_thetas; }
	/** Bearings, phiMin first. */
	const std::vector<double>& phis() const { return m_phis; }
	double phiCenter() const { return m_phiCenter; }
	const SensorSpec& spec() const { return m_spec; }
	const std::string& sensorLabel() const { return m_sensorLabel; }

private:
	const RayCaster& m_caster;
	SensorSpec m_spec;
	uint64_t m_seed;
	std::string m_sensorLabel;
	std::vector<double> m_thetas, m_phis, m_cosPhi, m_sinPhi;
	double m_phiCenter = 0;
	int m_threads = 0;
};

}  // namespace semnav
