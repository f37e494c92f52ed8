/* semnav: semantic navigation from tilting-laser sweeps */
// PredictionGuard: directions the update did not constrain follow the
// prediction, constrained ones keep the filter's correction, a posterior
// wider than the prediction is left alone; options are checked.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/poses/CPosePDFParticles.h>
#include <semnav/common/Error.h>
#include <semnav/localization/PredictionGuard.h>

#include <cmath>
#include <random>

using namespace semnav;

namespace
{
mrpt::math::CMatrixDouble33 diag(double sx, double sy, double syaw)
{
	mrpt::math::CMatrixDouble33 c;
	c.setZero();
	c(0, 0) = sx * sx;
	c(1, 1) = sy * sy;
	c(2, 2) = syaw * syaw;
	return c;
}

/** Prediction at (5, 2, 0): 0.3 m along x and y, 5 deg. */
mrpt::poses::CPosePDFGaussian prediction()
{
	return mrpt::poses::CPosePDFGaussian(
	    mrpt::poses::CPose2D(5, 2, 0), diag(0.3, 0.3, mrpt::DEG2RAD(5.0)));
}
}  // namespace

TEST(PredictionGuard, UnconstrainedDirectionFollowsThePrediction)
{
	// A wall along x: y and the heading shrink, x keeps its spread but the
	// mean moved 0.2 m (a biased likelihood).
	const PredictionGuard guard;
	const mrpt::poses::CPose2D post(4.8, 2.1, mrpt::DEG2RAD(1.0));
	const auto r =
	    guard.apply(prediction(), post, diag(0.29, 0.03, mrpt::DEG2RAD(0.5)));
	EXPECT_EQ(r.unconstrained, 1);
	EXPECT_NEAR(r.pose.x(), 5.0, 1e-6);
	EXPECT_NEAR(r.pose.y(), 2.1, 1e-6);
	EXPECT_NEAR(r.pose.phi(), mrpt::DEG2RAD(1.0), 1e-9);
	EXPECT_NEAR(r.shiftX, 0.2, 1e-6);
	EXPECT_NEAR(r.shiftY, 0.0, 1e-6);
	EXPECT_GT(r.maxVarianceRatio, 0.9);
}

TEST(PredictionGuard, ConstrainedAndConflictingUpdatesAreKept)
{
	const PredictionGuard guard;
	const mrpt::poses::CPose2D post(4.8, 2.1, mrpt::DEG2RAD(1.0));
	// Everything constrained (a post fixes x too): the filter's estimate.
	const auto a =
	    guard.apply(prediction(), post, diag(0.05, 0.03, mrpt::DEG2RAD(0.5)));
	EXPECT_EQ(a.unconstrained, 0);
	EXPECT_NEAR(a.pose.x(), 4.8, 1e-6);
	// Wider than the prediction along x (two modes): left to the filter.
	const auto b =
	    guard.apply(prediction(), post, diag(0.6, 0.03, mrpt::DEG2RAD(0.5)));
	EXPECT_EQ(b.unconstrained, 0);
	EXPECT_NEAR(b.pose.x(), 4.8, 1e-6);
	// Off: the filter's estimate, the ratio still reported.
	PredictionGuard::TOptions o;
	o.enabled = false;
	const auto c = PredictionGuard(o).apply(
	    prediction(), post, diag(0.29, 0.03, mrpt::DEG2RAD(0.5)));
	EXPECT_EQ(c.unconstrained, 0);
	EXPECT_NEAR(c.pose.x(), 4.8, 1e-6);
	EXPECT_GT(c.maxVarianceRatio, 0.9);
}

TEST(PredictionGuard, LargestStdAndItsDirection)
{
	mrpt::math::CMatrixDouble33 c = diag(0.1, 0.4, 0.01);
	double s = 0, dir = 0;
	PredictionGuard::largestStd(c, s, dir);
	EXPECT_NEAR(s, 0.4, 1e-9);
	EXPECT_NEAR(std::abs(dir), M_PI / 2, 1e-9);
}

TEST(PredictionGuard, OptionsRejectUnknownKeysAndOutOfRange)
{
	PredictionGuard::TOptions o;
	mrpt::config::CConfigFileMemory a;
	a.write("PredictionGuard", "variance_ratio", 0.5);
	EXPECT_THROW(o.loadFromConfigFile(a, "PredictionGuard"), ConfigError);
	mrpt::config::CConfigFileMemory b;
	b.write("PredictionGuard", "unconstrained_variance_ratio", 1.5);
	EXPECT_THROW(o.loadFromConfigFile(b, "PredictionGuard"), ConfigError);
	mrpt::config::CConfigFileMemory c;
	c.write("PredictionGuard", "unconstrained_variance_ratio", 0.8);
	c.write("PredictionGuard", "conflict_variance_ratio", 0.7);
	EXPECT_THROW(o.loadFromConfigFile(c, "PredictionGuard"), ConfigError);
}

namespace
{
/** `n` particles of equal weight, Gaussian around `c`. */
void addParticles(
    mrpt::poses::CPosePDFParticles& pdf, const mrpt::poses::CPose2D& c,
    std::size_t n, double stdXY, double stdYaw, std::mt19937& rng)
{
	std::normal_distribution<double> xy(0, stdXY), yaw(0, stdYaw);
	for (std::size_t i = 0; i < n; i++)
	{
		mrpt::poses::CPosePDFParticles::CParticleDataContent p(
		    c.x() + xy(rng), c.y() + xy(rng), c.phi() + yaw(rng));
		pdf.m_particles.emplace_back(p, 0.0);
	}
}
}  // namespace

TEST(PredictionGuard, HypothesisOfTwoModesHoldsOneModesWeight)
{
	// 70 % of the particles in a corridor heading west, 30 % 4 m north and
	// turned 90 deg (the mirror hypothesis): the estimate's hypothesis is
	// the corridor's alone, with its own small spread.
	std::mt19937 rng(3);
	mrpt::poses::CPosePDFParticles pdf;
	pdf.m_particles.clear();
	const mrpt::poses::CPose2D corridor(2.5, 1.2, M_PI);
	addParticles(pdf, corridor, 700, 0.1, mrpt::DEG2RAD(1.0), rng);
	addParticles(
	    pdf, mrpt::poses::CPose2D(2.5, 5.2, M_PI / 2), 300, 0.1,
	    mrpt::DEG2RAD(1.0), rng);
	const PredictionGuard guard;
	const auto h = guard.hypothesisOf(pdf, corridor);
	EXPECT_NEAR(h.weight, 0.7, 0.01);
	EXPECT_NEAR(h.mean.y(), 1.2, 0.03);
	EXPECT_LT(std::sqrt(h.cov(1, 1)), 0.15);
	const auto [cov, mean] = pdf.getCovarianceAndMean();
	EXPECT_GT(std::sqrt(cov(1, 1)), 1.5);
}

TEST(PredictionGuard, HypothesisOfOneWideModeIsAllParticles)
{
	// One hypothesis spread 0.8 m along a wall: all of it, however wide.
	std::mt19937 rng(5);
	mrpt::poses::CPosePDFParticles pdf;
	pdf.m_particles.clear();
	std::normal_distribution<double> along(0, 0.8), across(0, 0.05);
	for (int i = 0; i < 1000; i++)
		pdf.m_particles.emplace_back(
		    mrpt::poses::CPosePDFParticles::CParticleDataContent(
		        6 + along(rng), 7.5 + across(rng), M_PI),
		    0.0);
	const PredictionGuard guard;
	const auto h = guard.hypothesisOf(pdf, mrpt::poses::CPose2D(6, 7.5, M_PI));
	EXPECT_GT(h.weight, 0.99);
	EXPECT_NEAR(std::sqrt(h.cov(0, 0)), 0.8, 0.1);
}
