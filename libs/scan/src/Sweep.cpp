/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/scan/Sweep.h>

#include <cmath>
#include <limits>

namespace semnav
{
Sweep::Sweep(std::size_t rows, std::size_t cols)
    : m_rows(rows),
      m_cols(cols),
      m_range(rows * cols, 0.0f),
      m_valid(rows * cols, 0),
      m_theta(rows, 0.0),
      m_phi(cols, 0.0),
      m_cosPhi(cols, 1.0),
      m_sinPhi(cols, 0.0),
      m_sensorPose(rows)
{
}

std::size_t Sweep::validCount() const
{
	std::size_t n = 0;
	for (auto v : m_valid) n += v;
	return n;
}

void Sweep::setRow(
    std::size_t r, double theta, const mrpt::poses::CPose3D& sensorPose)
{
	m_theta[r] = theta;
	m_sensorPose[r] = sensorPose;
}

void Sweep::setPhis(const std::vector<double>& phi)
{
	m_phi = phi;
	m_cosPhi.resize(phi.size());
	m_sinPhi.resize(phi.size());
	for (std::size_t c = 0; c < phi.size(); c++)
	{
		m_cosPhi[c] = std::cos(phi[c]);
		m_sinPhi[c] = std::sin(phi[c]);
	}
}

mrpt::math::TPoint3Df Sweep::point(std::size_t r, std::size_t c) const
{
	const double d = range(r, c);
	double x, y, z;
	m_sensorPose[r].composePoint(
	    d * m_cosPhi[c], d * m_sinPhi[c], 0.0, x, y, z);
	return {
	    static_cast<float>(x), static_cast<float>(y), static_cast<float>(z)};
}

std::vector<mrpt::math::TPoint3Df> Sweep::points() const
{
	constexpr float nan = std::numeric_limits<float>::quiet_NaN();
	std::vector<mrpt::math::TPoint3Df> out(m_rows * m_cols, {nan, nan, nan});
	for (std::size_t r = 0; r < m_rows; r++)
		for (std::size_t c = 0; c < m_cols; c++)
			if (valid(r, c)) out[r * m_cols + c] = point(r, c);
	return out;
}

}  // namespace semnav
