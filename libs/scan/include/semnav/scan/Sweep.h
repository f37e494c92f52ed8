/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/core/Clock.h>
#include <mrpt/math/TPoint3D.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/poses/CPose3D.h>
#include <semnav/scan/SweepQuality.h>

#include <cstdint>
#include <string>
#include <vector>

namespace semnav
{
/** One 3D sweep of a tilting 2D laser as an organized range image.
 *
 * Row r is one scan line at tilt theta(r), ordered by increasing tilt
 * (row 0 = lowest, whatever the nodding direction); column c is the beam at
 * bearing phi(c), column 0 = phi_min (the robot's right). Each row keeps the
 * scanner pose of its line in the robot frame, so points are exact even when
 * the laser is not on the tilt axis. Ranges are metres; invalid pixels (no
 * return, too close, missing line) have valid() == false. */
class Sweep
{
public:
	Sweep() = default;
	/** All pixels invalid, theta/phi zero, poses identity. */
	Sweep(std::size_t rows, std::size_t cols);

	std::size_t rows() const { return m_rows; }
	std::size_t cols() const { return m_cols; }
	bool empty() const { return m_rows == 0 || m_cols == 0; }

	float range(std::size_t r, std::size_t c) const
	{
		return m_range[r * m_cols + c];
	}
	bool valid(std::size_t r, std::size_t c) const
	{
		return m_valid[r * m_cols + c] != 0;
	}
	void setRange(std::size_t r, std::size_t c, float range, bool valid)
	{
		m_range[r * m_cols + c] = range;
		m_valid[r * m_cols + c] = valid ? 1 : 0;
	}
	/** Row-major ranges (rows() x cols()). */
	const std::vector<float>& ranges() const { return m_range; }
	/** Row-major validity flags, 1 = valid. */
	const std::vector<uint8_t>& validity() const { return m_valid; }
	std::size_t validCount() const;

	double theta(std::size_t r) const { return m_theta[r]; }
	double phi(std::size_t c) const { return m_phi[c]; }
	const std::vector<double>& thetas() const { return m_theta; }
	const std::vector<double>& phis() const { return m_phi; }
	/** Scanner pose of row r in the robot frame. */
	const mrpt::poses::CPose3D& sensorPose(std::size_t r) const
	{
		return m_sensorPose[r];
	}
	void setRow(
	    std::size_t r, double theta, const mrpt::poses::CPose3D& sensorPose);
	/** Bearings; the beam at phi(c) has direction (cos, sin, 0) in the
	 * scanner frame of its row. */
	void setPhis(const std::vector<double>& phi);

	/** 3D point of pixel (r, c) in the robot frame (valid pixels only). */
	mrpt::math::TPoint3Df point(std::size_t r, std::size_t c) const;
	/** All pixels' points in the robot frame, row-major; invalid ones NaN. */
	std::vector<mrpt::math::TPoint3Df> points() const;

	/** Odometry pose of the robot during the sweep (stop-and-scan). */
	const mrpt::poses::CPose2D& odometry() const { return m_odometry; }
	bool hasOdometry() const { return m_hasOdometry; }
	void setOdometry(const mrpt::poses::CPose2D& p)
	{
		m_odometry = p;
		m_hasOdometry = true;
	}

	mrpt::Clock::time_point timestamp() const { return m_timestamp; }
	void setTimestamp(mrpt::Clock::time_point t) { m_timestamp = t; }

	const std::string& sensorLabel() const { return m_sensorLabel; }
	void setSensorLabel(const std::string& s) { m_sensorLabel = s; }

	float maxRange() const { return m_maxRange; }
	void setMaxRange(float r) { m_maxRange = r; }

	/** Index of the sweep in its log (0-based). */
	std::size_t index() const { return m_index; }
	void setIndex(std::size_t i) { m_index = i; }

	const SweepQuality& quality() const { return m_quality; }
	SweepQuality& quality() { return m_quality; }

private:
	std::size_t m_rows = 0, m_cols = 0;
	std::vector<float> m_range;
	std::vector<uint8_t> m_valid;
	std::vector<double> m_theta, m_phi, m_cosPhi, m_sinPhi;
	std::vector<mrpt::poses::CPose3D> m_sensorPose;
	mrpt::poses::CPose2D m_odometry;
	bool m_hasOdometry = false;
	mrpt::Clock::time_point m_timestamp{};
	std::string m_sensorLabel;
	float m_maxRange = 0;
	std::size_t m_index = 0;
	SweepQuality m_quality;
};

}  // namespace semnav
