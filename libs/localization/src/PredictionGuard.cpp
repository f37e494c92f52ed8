/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/math/wrap2pi.h>
#include <semnav/common/OptionTable.h>
#include <semnav/localization/PredictionGuard.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace semnav
{
namespace
{
using O = PredictionGuard::TOptions;
const OptionTable<O>& optionTable()
{
	static const auto t =
	    OptionTable<O>()
	        .flag(
	            "enabled", &O::enabled,
	            "Mapping: along directions the sweep does not constrain, the "
	            "estimate follows the motion prediction.")
	        .real(
	            "unconstrained_variance_ratio", &O::unconstrainedVarianceRatio,
	            0.01, 1,
	            "A direction whose posterior variance is above this fraction "
	            "of the predicted one is unconstrained.");
	return t;
}

/** Covariances from particles can be singular (one heading for all). */
Eigen::Matrix3d regularized(const mrpt::math::CMatrixDouble33& c)
{
	Eigen::Matrix3d m = c.asEigen();
	m = 0.5 * (m + m.transpose());
	const double eps[3] = {1e-8, 1e-8, 1e-10};
	for (int i = 0; i < 3; i++) m(i, i) += eps[i];
	return m;
}
}  // namespace

SEMNAV_OPTIONS_FROM_TABLE(PredictionGuard::TOptions, optionTable())

mrpt::poses::CPosePDFGaussian PredictionGuard::predict(
    const mrpt::poses::CPosePDFGaussian& prior,
    const mrpt::poses::CPosePDFGaussian& increment)
{
	mrpt::poses::CPosePDFGaussian p = prior;
	p += increment;
	return p;
}

PredictionGuard::Result PredictionGuard::apply(
    const mrpt::poses::CPosePDFGaussian& predicted,
    const mrpt::poses::CPose2D& posteriorMean,
    const mrpt::math::CMatrixDouble33& posteriorCov) const
{
	Result r;
	r.pose = posteriorMean;
	const Eigen::Matrix3d S = regularized(predicted.cov);
	const Eigen::Matrix3d P = regularized(posteriorCov);
	// P v = lambda S v; V^T S V = I, so the correction's coordinates in the
	// eigenvector basis are V^T S delta.
	const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix3d> es(P, S);
	if (es.info() != Eigen::Success) return r;
	const Eigen::Matrix3d V = es.eigenvectors();
	const Eigen::Vector3d lambda = es.eigenvalues();
	r.maxVarianceRatio = lambda.maxCoeff();
	if (!m_options.enabled) return r;
	const auto& m = predicted.mean;
	const Eigen::Vector3d delta(
	    posteriorMean.x() - m.x(), posteriorMean.y() - m.y(),
	    mrpt::math::wrapToPi(posteriorMean.phi() - m.phi()));
	Eigen::Vector3d c = V.transpose() * S * delta;
	for (int i = 0; i < 3; i++)
		if (lambda(i) > m_options.unconstrainedVarianceRatio)
		{
			c(i) = 0;
			r.unconstrained++;
		}
	const Eigen::Vector3d kept = V * c;
	r.shiftX = kept(0) - delta(0);
	r.shiftY = kept(1) - delta(1);
	r.shiftYaw = kept(2) - delta(2);
	r.pose = mrpt::poses::CPose2D(
	    m.x() + kept(0), m.y() + kept(1),
	    mrpt::math::wrapToPi(m.phi() + kept(2)));
	return r;
}

void PredictionGuard::largestStd(
    const mrpt::math::CMatrixDouble33& cov, double& stdMax, double& direction)
{
	Eigen::Matrix2d c = cov.asEigen().topLeftCorner<2, 2>();
	c = 0.5 * (c + c.transpose());
	const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(c);
	const Eigen::Vector2d v = es.eigenvectors().col(1);
	stdMax = std::sqrt(std::max(0.0, es.eigenvalues()(1)));
	direction = std::atan2(v(1), v(0));
	if (direction <= -M_PI / 2) direction += M_PI;
	if (direction > M_PI / 2) direction -= M_PI;
}

}  // namespace semnav
