/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/math/wrap2pi.h>
#include <semnav/common/OptionTable.h>
#include <semnav/localization/PredictionGuard.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <tuple>
#include <vector>

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
	            "of the predicted one is unconstrained...")
	        .real(
	            "conflict_variance_ratio", &O::conflictVarianceRatio,
	            &O::unconstrainedVarianceRatio, 100,
	            "...unless above this: a posterior wider than the prediction "
	            "means the sweep disagrees with it (the filter decides).")
	        .real(
	            "unimodal_weight", &O::unimodalWeight, 0, 1,
	            "Particles connected to the estimate holding less than this "
	            "share of the weight: several hypotheses; only the estimate's "
	            "is tested.")
	        .real(
	            "cluster_cell_m", &O::clusterCellM, 0.01, 10,
	            "Cells of the hypotheses' connection test (cells holding 0.1 % "
	            "of the weight connect over gaps of up to two cells)...")
	        .angle(
	            "cluster_cell_yaw_deg", &O::clusterCellYaw, 0.1, 180,
	            "...and their heading size.");
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
	const auto& m = predicted.mean;
	// Heading first, alone: the main directions fix it or nothing does.
	const double yawRatio = P(2, 2) / S(2, 2);
	double yaw = posteriorMean.phi();
	const bool yawFree = unconstrained(yawRatio);
	if (m_options.enabled && yawFree)
	{
		yaw = m.phi();
		r.unconstrained++;
	}
	// Position: the prediction given that heading (Gaussian conditioning),
	// against the posterior, by generalised eigen-direction: P v = l S v,
	// V^T S V = I, so the correction's coordinates are V^T S delta.
	const Eigen::Vector2d sxy = S.block<2, 1>(0, 2);
	const Eigen::Matrix2d Sc =
	    S.topLeftCorner<2, 2>() - sxy * sxy.transpose() / S(2, 2);
	const Eigen::Vector2d mc =
	    Eigen::Vector2d(m.x(), m.y()) +
	    sxy / S(2, 2) * mrpt::math::wrapToPi(yaw - m.phi());
	const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d> es(
	    P.topLeftCorner<2, 2>(), Sc);
	if (es.info() != Eigen::Success) return r;
	const Eigen::Matrix2d V = es.eigenvectors();
	const Eigen::Vector2d lambda = es.eigenvalues();
	r.maxVarianceRatio = std::max(yawRatio, lambda.maxCoeff());
	if (!m_options.enabled) return r;
	const Eigen::Vector2d delta =
	    Eigen::Vector2d(posteriorMean.x(), posteriorMean.y()) - mc;
	Eigen::Vector2d c = V.transpose() * Sc * delta;
	for (int i = 0; i < 2; i++)
		if (unconstrained(lambda(i)))
		{
			c(i) = 0;
			r.unconstrained++;
		}
	const Eigen::Vector2d xy = mc + V * c;
	r.shiftX = xy(0) - posteriorMean.x();
	r.shiftY = xy(1) - posteriorMean.y();
	r.shiftYaw = mrpt::math::wrapToPi(yaw - posteriorMean.phi());
	r.pose = mrpt::poses::CPose2D(xy(0), xy(1), yaw);
	return r;
}

PredictionGuard::Hypothesis PredictionGuard::hypothesisOf(
    const mrpt::poses::CPosePDFParticles& pdf,
    const mrpt::poses::CPose2D& mode) const
{
	const double cell = m_options.clusterCellM;
	const double cellYaw = m_options.clusterCellYaw;
	using Key = std::tuple<int, int, int>;
	const auto key = [&](const mrpt::math::TPose2D& p)
	{
		return Key(
		    int(std::floor(p.x / cell)), int(std::floor(p.y / cell)),
		    int(std::floor(mrpt::math::wrapTo2Pi(p.phi) / cellYaw)));
	};
	const int yawCells = int(std::ceil(2 * M_PI / cellYaw));
	std::map<Key, double> weight;
	double total = 0;
	for (const auto& p : pdf.m_particles)
	{
		const double w = std::exp(p.log_w);
		weight[key(p.d)] += w;
		total += w;
	}
	std::set<Key> reached = {key(mode.asTPose())};
	std::vector<Key> open(reached.begin(), reached.end());
	while (!open.empty())
	{
		const auto [kx, ky, kyaw] = open.back();
		open.pop_back();
		for (int dx = -2; dx <= 2; dx++)
			for (int dy = -2; dy <= 2; dy++)
				for (int da = -2; da <= 2; da++)
				{
					const Key k(
					    kx + dx, ky + dy, (kyaw + da + yawCells) % yawCells);
					const auto it = weight.find(k);
					if (it == weight.end() || it->second < 1e-3 * total ||
					    !reached.insert(k).second)
						continue;
					open.push_back(k);
				}
	}
	double sw = 0, sx = 0, sy = 0, ss = 0, sc = 0;
	std::vector<std::pair<const mrpt::math::TPose2D*, double>> members;
	for (const auto& p : pdf.m_particles)
	{
		if (!reached.count(key(p.d))) continue;
		const double w = std::exp(p.log_w);
		members.emplace_back(&p.d, w);
		sw += w, sx += w * p.d.x, sy += w * p.d.y;
		ss += w * std::sin(p.d.phi), sc += w * std::cos(p.d.phi);
	}
	Hypothesis c;
	if (sw <= 0) return c;
	c.weight = sw / total;
	c.mean = mrpt::poses::CPose2D(sx / sw, sy / sw, std::atan2(ss, sc));
	c.cov.setZero();
	for (const auto& [p, w] : members)
	{
		const double d[3] = {
		    p->x - c.mean.x(), p->y - c.mean.y(),
		    mrpt::math::wrapToPi(p->phi - c.mean.phi())};
		for (int i = 0; i < 3; i++)
			for (int j = 0; j < 3; j++) c.cov(i, j) += w / sw * d[i] * d[j];
	}
	return c;
}
bool PredictionGuard::unconstrained(double varianceRatio) const
{
	return varianceRatio > m_options.unconstrainedVarianceRatio &&
	       varianceRatio <= m_options.conflictVarianceRatio;
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
