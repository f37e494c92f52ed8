/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/math/CMatrixFixed.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/poses/CPosePDFGaussian.h>
#include <mrpt/poses/CPosePDFParticles.h>

#include <string>

namespace semnav
{
/** Keeps a pose-tracking filter from drifting along directions its
 * evidence does not fix (a single long wall, an open lawn): there the
 * estimate follows the motion prediction (the previous estimate moved by
 * the odometry increment) instead of whatever slow bias the likelihood has.
 *
 * The test compares the posterior covariance P (the particles after the
 * update) with the predicted covariance S (the previous posterior composed
 * with the motion model's increment, first-order) direction by direction:
 * the generalised eigenproblem P v = lambda S v, i.e. the eigenvalues of
 * S^-1/2 P S^-1/2 in the whitened prediction space (unit free: x, y and
 * yaw together). lambda is the fraction of the predicted variance left
 * along v; lambda near 1 means the sweep brought no information there. The
 * correction (posterior mean minus predicted mean), whitened, loses its
 * components along the eigenvectors with lambda above
 * `unconstrained_variance_ratio` (and not above `conflict_variance_ratio`:
 * a posterior wider than the prediction is no lack of information but a
 * disagreement, left to the filter); what remains is the estimate, and the
 * particles are moved by the dropped part so that the filter agrees with it.
 * The spread along those directions is left as it is: the reported
 * covariance says the direction is unknown.
 * While mapping, a posterior of several hypotheses (hypothesisOf() holds
 * less than `unimodal_weight` of the weight) is tested by the estimate's
 * hypothesis alone: the spread between hypotheses is no lack of
 * information.
 *
 * Options: INI section [PredictionGuard] (config/localization.ini). */
class PredictionGuard
{
public:
	struct TOptions : public mrpt::config::CLoadableOptions
	{
		void loadFromConfigFile(
		    const mrpt::config::CConfigFileBase& c,
		    const std::string& section) override;
		void saveToConfigFile(
		    mrpt::config::CConfigFileBase& c,
		    const std::string& section) const override;

		/** enabled: apply the guard (off: the filter's estimate as is). */
		bool enabled = true;
		/** unconstrained_variance_ratio: a direction whose posterior
		 * variance is above this fraction of the predicted one follows
		 * the prediction. */
		double unconstrainedVarianceRatio = 0.65;
		/** conflict_variance_ratio: ...unless the posterior is wider than
		 * this fraction of the prediction: then the sweep disagrees with
		 * the prediction (two modes, a wrong prediction) and the filter's
		 * estimate stands. */
		double conflictVarianceRatio = 1.25;
		/** unimodal_weight: when the particles connected to the estimate
		 * (cells of cluster_cell_m m, gaps up to two cells) hold less than
		 * this share of the weight, the posterior has several hypotheses
		 * and only the estimate's is tested (mapping). */
		double unimodalWeight = 0.9;
		/** cluster_cell_m, cluster_cell_yaw_deg: cells of that test; cells
		 * holding at least 0.1 % of the weight connect over gaps of up
		 * to two cells. */
		double clusterCellM = 0.25;
		double clusterCellYaw = mrpt::DEG2RAD(10.0);
	};

	/** What the guard decided for one update. */
	struct Result
	{
		/** The estimate (prediction plus the trusted correction). */
		mrpt::poses::CPose2D pose;
		/** Dropped part of the correction: add it to every particle. */
		double shiftX = 0, shiftY = 0, shiftYaw = 0;
		/** Directions (of 3) that followed the prediction. */
		int unconstrained = 0;
		/** Largest fraction of the predicted variance left (lambda max). */
		double maxVarianceRatio = 0;
	};

	PredictionGuard() = default;
	explicit PredictionGuard(const TOptions& o) : m_options(o) {}

	/** The prediction: `prior` composed with the increment (mean and
	 * covariance of the motion model, robot frame). */
	static mrpt::poses::CPosePDFGaussian predict(
	    const mrpt::poses::CPosePDFGaussian& prior,
	    const mrpt::poses::CPosePDFGaussian& increment);

	/** Applies the test to a posterior (mean, covariance). */
	Result apply(
	    const mrpt::poses::CPosePDFGaussian& predicted,
	    const mrpt::poses::CPose2D& posteriorMean,
	    const mrpt::math::CMatrixDouble33& posteriorCov) const;

	/** The particles of one hypothesis: mean, covariance and share of the
	 * weight. */
	struct Hypothesis
	{
		mrpt::poses::CPose2D mean;
		mrpt::math::CMatrixDouble33 cov;
		double weight = 0;
	};
	/** The hypothesis `pose` belongs to: the particles whose cells
	 * (cluster_cell_m, cluster_cell_yaw_deg) connect to the cell of `pose`
	 * through cells within two cells of each other that hold at least
	 * 0.1 % of the weight. */
	Hypothesis hypothesisOf(
	    const mrpt::poses::CPosePDFParticles& pdf,
	    const mrpt::poses::CPose2D& pose) const;

	/** Largest std dev of an xy covariance (m) and its direction (rad, in
	 * (-pi/2, pi/2]). */
	static void largestStd(
	    const mrpt::math::CMatrixDouble33& cov, double& stdMax,
	    double& direction);

	const TOptions& options() const { return m_options; }
	/** True for a fraction of the predicted variance that marks an
	 * unconstrained direction. */
	bool unconstrained(double varianceRatio) const;

private:
	TOptions m_options;
};

}  // namespace semnav
