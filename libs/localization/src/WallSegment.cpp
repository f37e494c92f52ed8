/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/localization/WallSegment.h>

#include <Eigen/Eigenvalues>
#include <algorithm>

namespace semnav
{
WallSegment fitWallSegment(
    const std::vector<double>& xs, const std::vector<double>& ys,
    double endpointQuantile)
{
	const std::size_t n = xs.size();
	double mx = 0, my = 0;
	for (std::size_t i = 0; i < n; i++) mx += xs[i], my += ys[i];
	mx /= n, my /= n;
	double sxx = 0, sxy = 0, syy = 0;
	for (std::size_t i = 0; i < n; i++)
	{
		const double dx = xs[i] - mx, dy = ys[i] - my;
		sxx += dx * dx, sxy += dx * dy, syy += dy * dy;
	}
	Eigen::Matrix2d cov;
	cov << sxx / n, sxy / n, sxy / n, syy / n;
	Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(cov);
	const double lMin = std::max(0.0, es.eigenvalues()(0));
	const double lMax = std::max(1e-12, es.eigenvalues()(1));
	const Eigen::Vector2d d = es.eigenvectors().col(1);
	std::vector<double> along(n);
	for (std::size_t i = 0; i < n; i++)
		along[i] = (xs[i] - mx) * d.x() + (ys[i] - my) * d.y();
	const auto q = [&](double f)
	{
		const std::size_t k =
		    std::min(n - 1, static_cast<std::size_t>(std::lround(f * (n - 1))));
		std::nth_element(along.begin(), along.begin() + k, along.end());
		return along[k];
	};
	const double t0 = q(endpointQuantile), t1 = q(1 - endpointQuantile);
	WallSegment s;
	s.p0 = {mx + t0 * d.x(), my + t0 * d.y()};
	s.p1 = {mx + t1 * d.x(), my + t1 * d.y()};
	s.points = n;
	s.residual = std::sqrt(lMin);
	// Line fit: var(offset) = s^2 / n, var(angle) = s^2 / (n var_along).
	s.sigmaOffset = s.residual / std::sqrt(double(n));
	s.sigmaAngle = s.residual / std::sqrt(double(n) * lMax);
	return s;
}
}  // namespace semnav
