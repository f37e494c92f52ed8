/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/math/wrap2pi.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/random/RandomGenerators.h>
#include <semnav/common/Error.h>
#include <semnav/common/OptionTable.h>
#include <semnav/localization/Localizer.h>
#include <semnav/localization/PredictionGuard.h>
#include <semnav/map/SemanticMap.h>

#include <chrono>
#include <cmath>
#include <map>
#include <tuple>

namespace semnav
{

namespace
{
using O = Localizer::TOptions;
const OptionTable<O>& optionTable()
{
	static const auto t =
	    OptionTable<O>()
	        .integer(
	            "particles", &O::particles, 1, 10000000,
	            "Particles of a pose-tracking start.")
	        .integer(
	            "global_particles", &O::globalParticles, 1, 10000000,
	            "Particles of a global start.")
	        .flag(
	            "adaptive_sample_size", &O::adaptiveSampleSize,
	            "KLD adaptive sample size (MRPT TKLDParams).")
	        .real("kld_bin_xy_m", &O::kldBinXY, 0.001, 10, "KLD bin size.")
	        .angle("kld_bin_yaw_deg", &O::kldBinYaw, 0.01, 180, "KLD bin size.")
	        .real("kld_delta", &O::kldDelta, 1e-6, 0.999, "KLD delta.")
	        .real("kld_epsilon", &O::kldEpsilon, 1e-6, 10, "KLD epsilon.")
	        .integer(
	            "kld_min_samples", &O::kldMinSamples, 1, 10000000,
	            "KLD sample size bounds.")
	        .integer(
	            "kld_max_samples", &O::kldMaxSamples, &O::kldMinSamples,
	            10000000, "KLD sample size bounds.")
	        .real(
	            "ess_threshold", &O::essThreshold, 0, 1,
	            "Resample when the effective sample size fraction drops "
	            "below.")
	        .real(
	            "motion_xy_per_m", &O::motionXYPerMeter, 0, 10,
	            "Motion model: std of x, y per metre travelled.")
	        .angle(
	            "motion_yaw_deg_per_m", &O::motionYawPerMeter, 0, 180,
	            "Motion model: std of yaw per metre travelled.")
	        .real(
	            "motion_yaw_per_rad", &O::motionYawPerRad, 0, 10,
	            "Motion model: std of yaw per radian turned.")
	        .real(
	            "motion_min_xy_m", &O::motionMinXY, 0, 10,
	            "Motion model: minimum std of x, y.")
	        .angle(
	            "motion_min_yaw_deg", &O::motionMinYaw, 0, 180,
	            "Motion model: minimum std of yaw.")
	        .real(
	            "initial_std_xy_m", &O::initialStdXY, 0, 100,
	            "Spread of a pose-tracking start.")
	        .angle(
	            "initial_std_yaw_deg", &O::initialStdYaw, 0, 180,
	            "Spread of a pose-tracking start.")
	        .flag(
	            "main_directions", &O::mainDirections,
	            "Main-direction heading correction in the propagation.")
	        .angle(
	            "heading_noise_deg", &O::headingNoise, 0, 45,
	            "Noise added to the corrected heading.")
	        .angle(
	            "max_correction_deg", &O::maxCorrection, 0, 45,
	            "Largest heading correction.")
	        .real(
	            "effective_points", &O::effectivePoints, 0.01, 1e6,
	            "Log-likelihood scaled to this many independent samples "
	            "per sweep.")
	        .real(
	            "global_effective_points", &O::globalEffectivePoints, 0.01, 1e6,
	            "The same after a global start, until converged.")
	        .real(
	            "converged_std_xy_m", &O::convergedStdXY, 0, 100,
	            "Converged when the spread is below this...")
	        .angle(
	            "converged_std_yaw_deg", &O::convergedStdYaw, 0, 180,
	            "...and this.")
	        .flag(
	            "kidnap_detection", &O::kidnapDetection,
	            "Known map: restart globally when the walls stop matching.")
	        .real(
	            "kidnap_inlier_fraction", &O::kidnapInlierFraction, 0, 1,
	            "Kidnapped: fewer wall samples than this within 2 sigma of "
	            "a map wall...")
	        .integer(
	            "kidnap_updates", &O::kidnapUpdates, 1, 1000,
	            "...for this many updates.")
	        .real(
	            "free_cell_threshold", &O::freeCellThreshold, 0, 1,
	            "Global starts use seen cells with occupancy below this.")
	        .integer(
	            "seed", &O::seed, 0, 1 << 30,
	            "Random seed (MRPT's generator).");
	return t;
}
}  // namespace

SEMNAV_OPTIONS_FROM_TABLE(Localizer::TOptions, optionTable())

mrpt::bayes::CParticleFilter::TParticleFilterOptions Localizer::pfOptions(
    const TOptions& o)
{
	mrpt::bayes::CParticleFilter::TParticleFilterOptions p;
	p.PF_algorithm = mrpt::bayes::CParticleFilter::pfStandardProposal;
	// MRPT draws KLD samples by multinomial resampling only.
	p.resamplingMethod = o.adaptiveSampleSize
	                         ? mrpt::bayes::CParticleFilter::prMultinomial
	                         : mrpt::bayes::CParticleFilter::prSystematic;
	p.adaptiveSampleSize = o.adaptiveSampleSize;
	p.BETA = o.essThreshold;
	return p;
}

mrpt::obs::CActionRobotMovement2D::TMotionModelOptions Localizer::motionOptions(
    const TOptions& o)
{
	mrpt::obs::CActionRobotMovement2D::TMotionModelOptions m;
	m.modelSelection = mrpt::obs::CActionRobotMovement2D::mmGaussian;
	m.gaussianModel.a1 = o.motionXYPerMeter;
	m.gaussianModel.a2 = 0;
	m.gaussianModel.a3 = o.motionYawPerMeter;
	m.gaussianModel.a4 = o.motionYawPerRad;
	m.gaussianModel.minStdXY = o.motionMinXY;
	m.gaussianModel.minStdPHI = o.motionMinYaw;
	return m;
}

void Localizer::kldOptions(const TOptions& o, mrpt::slam::TKLDParams& k)
{
	k.KLD_binSize_XY = o.kldBinXY;
	k.KLD_binSize_PHI = o.kldBinYaw;
	k.KLD_delta = o.kldDelta;
	k.KLD_epsilon = o.kldEpsilon;
	k.KLD_minSampleSize = static_cast<unsigned>(o.kldMinSamples);
	k.KLD_maxSampleSize = static_cast<unsigned>(o.kldMaxSamples);
}

LocalizationUpdate Localizer::summarize(
    const mrpt::poses::CPosePDFParticles& pdf, const TOptions& o)
{
	LocalizationUpdate u;
	const auto [cov, mean] = pdf.getCovarianceAndMean();
	u.stdXY = std::sqrt(std::max(0.0, cov(0, 0) + cov(1, 1)));
	u.stdYaw = std::sqrt(std::max(0.0, cov(2, 2)));
	u.cov = cov;
	PredictionGuard::largestStd(cov, u.largestStd, u.largestStdDirection);
	u.particles = pdf.size();
	u.ess = pdf.ESS();
	u.converged = u.stdXY <= o.convergedStdXY && u.stdYaw <= o.convergedStdYaw;
	u.pose = mean;
	if (u.converged || pdf.size() == 0) return u;
	// Several hypotheses: the mean may lie between them. Take the heaviest
	// cell of a coarse (0.25 m, 10 deg) histogram, then the weighted mean of
	// the particles near it.
	const double bxy = 0.25, byaw = mrpt::DEG2RAD(10);
	std::map<std::tuple<int, int, int>, double> bins;
	const auto key = [&](const mrpt::math::TPose2D& p)
	{
		return std::make_tuple(
		    int(std::floor(p.x / bxy)), int(std::floor(p.y / bxy)),
		    int(std::floor(mrpt::math::wrapTo2Pi(p.phi) / byaw)));
	};
	double best = -1;
	std::tuple<int, int, int> bestKey;
	for (std::size_t i = 0; i < pdf.size(); i++)
	{
		const auto k = key(pdf.m_particles[i].d);
		const double w = (bins[k] += std::exp(pdf.getW(i)));
		if (w > best) best = w, bestKey = k;
	}
	const mrpt::math::TPose2D c(
	    (std::get<0>(bestKey) + 0.5) * bxy, (std::get<1>(bestKey) + 0.5) * bxy,
	    (std::get<2>(bestKey) + 0.5) * byaw);
	double sw = 0, sx = 0, sy = 0, ss = 0, sc = 0;
	for (std::size_t i = 0; i < pdf.size(); i++)
	{
		const auto& p = pdf.m_particles[i].d;
		const double dyaw = mrpt::math::wrapToPi(p.phi - c.phi);
		if (std::hypot(p.x - c.x, p.y - c.y) > 2 * bxy ||
		    std::abs(dyaw) > 2 * byaw)
			continue;
		const double w = std::exp(pdf.getW(i));
		sw += w, sx += w * p.x, sy += w * p.y;
		ss += w * std::sin(p.phi), sc += w * std::cos(p.phi);
	}
	if (sw > 0)
		u.pose = mrpt::poses::CPose2D(sx / sw, sy / sw, std::atan2(ss, sc));
	return u;
}

Localizer::Localizer() : Localizer(TOptions()) {}

void Localizer::seedRandomGenerator(int seed)
{
	mrpt::random::getRandomGenerator() =
	    mrpt::random::CRandomGenerator(static_cast<uint32_t>(seed));
}

Localizer::Localizer(const TOptions& options)
    : mrpt::system::COutputLogger("Localizer"), m_options(options)
{
	m_pf.m_options = pfOptions(m_options);
	kldOptions(m_options, m_pdf.options.KLD_params);
	seedRandomGenerator(m_options.seed);
	m_pdf.seed(static_cast<uint32_t>(m_options.seed) + 1);
}

void Localizer::setWallMap(const WallMap* map)
{
	m_map = map;
	m_pdf.setWallMap(map);
}

void Localizer::setKnownMap(const SemanticMap& map)
{
	m_knownWalls = WallMap();
	m_knownWalls.buildFromSemanticMap(map);
	m_freeGeometry = map.geometry();
	m_free.assign(m_freeGeometry.cellCount(), 0);
	m_freeCount = 0;
	markFreeCells(map, CellRect::all(m_freeGeometry));
	m_known = &map;
	m_knownVersion = map.version();
	if (m_freeCount == 0)
		throw Error("Localizer: the known map has no free cell");
	setWallMap(&m_knownWalls);
}

void Localizer::updateKnownMap(const SemanticMap& map)
{
	const SemanticMap::Changes changes = map.changesSince(m_knownVersion);
	if (m_known != &map || changes.all || !(map.geometry() == m_freeGeometry))
	{
		setKnownMap(map);
		return;
	}
	m_knownWalls.updateFromSemanticMap(map);
	markFreeCells(map, changes.touched);
	m_knownVersion = map.version();
	if (m_freeCount == 0)
		throw Error("Localizer: the known map has no free cell");
	setWallMap(&m_knownWalls);
}

void Localizer::markFreeCells(const SemanticMap& map, const CellRect& cells)
{
	const auto& observations = map.get("observations");
	for (int cy = cells.row0; cy < cells.row1; cy++)
		for (int cx = cells.col0; cx < cells.col1; cx++)
		{
			const std::size_t i = m_freeGeometry.index(cy, cx);
			const uint8_t free =
			    observations[i] > 0 &&
			    map.occupancy(cx, cy) < m_options.freeCellThreshold;
			m_freeCount += free;
			m_freeCount -= m_free[i];
			m_free[i] = free;
		}
}

std::vector<mrpt::math::TPoint2D> Localizer::freeCells() const
{
	std::vector<mrpt::math::TPoint2D> out;
	out.reserve(m_freeCount);
	const GridGeometry& g = m_freeGeometry;
	for (int cy = 0; cy < g.rows; cy++)
		for (int cx = 0; cx < g.cols; cx++)
			if (m_free[g.index(cy, cx)])
				out.push_back({g.centerX(cx), g.centerY(cy)});
	return out;
}

void Localizer::initialize(const mrpt::poses::CPose2D& pose)
{
	m_pdf.resetDeterministic(
	    pose.asTPose(), static_cast<std::size_t>(m_options.particles));
	auto& rng = mrpt::random::getRandomGenerator();
	for (auto& p : m_pdf.m_particles)
	{
		p.d.x += rng.drawGaussian1D(0, m_options.initialStdXY);
		p.d.y += rng.drawGaussian1D(0, m_options.initialStdXY);
		p.d.phi = mrpt::math::wrapToPi(
		    p.d.phi + rng.drawGaussian1D(0, m_options.initialStdYaw));
	}
	m_lowInlierUpdates = 0;
}

void Localizer::initializeGlobal()
{
	if (m_freeCount == 0)
		throw Error("Localizer: global localization needs a known map");
	const std::vector<mrpt::math::TPoint2D> free = freeCells();
	auto& rng = mrpt::random::getRandomGenerator();
	const std::size_t n = static_cast<std::size_t>(m_options.globalParticles);
	m_pdf.resetDeterministic(mrpt::math::TPose2D(0, 0, 0), n);
	const double h = m_freeGeometry.resolution / 2;
	for (auto& p : m_pdf.m_particles)
	{
		const auto& c = free[rng.drawUniform32bit() % free.size()];
		p.d.x = c.x + rng.drawUniform(-h, h);
		p.d.y = c.y + rng.drawUniform(-h, h);
		p.d.phi = rng.drawUniform(-M_PI, M_PI);
	}
	m_lowInlierUpdates = 0;
	m_global = true;
	m_globalUpdates = 0;
	m_convergedAfter = -1;
}

void Localizer::initializeAround(
    const std::vector<mrpt::math::TPose2D>& poses, double stdXY, double stdYaw)
{
	if (poses.empty()) throw Error("Localizer: no poses to initialize around");
	auto& rng = mrpt::random::getRandomGenerator();
	const std::size_t n = static_cast<std::size_t>(m_options.globalParticles);
	m_pdf.resetDeterministic(mrpt::math::TPose2D(0, 0, 0), n);
	for (std::size_t i = 0; i < n; i++)
	{
		auto& p = m_pdf.m_particles[i].d;
		const mrpt::math::TPose2D& c = poses[i % poses.size()];
		p.x = c.x + rng.drawGaussian1D(0, stdXY);
		p.y = c.y + rng.drawGaussian1D(0, stdXY);
		p.phi = mrpt::math::wrapToPi(c.phi + rng.drawGaussian1D(0, stdYaw));
	}
	m_lowInlierUpdates = 0;
}

LocalizationUpdate Localizer::update(
    const mrpt::poses::CPose2D& odometryIncrement, const WallObservation& obs,
    const SemanticObservation* semantic)
{
	const auto t0 = std::chrono::steady_clock::now();
	mrpt::obs::CActionRobotMovement2D act;
	act.computeFromOdometry(odometryIncrement, motionOptions(m_options));
	mrpt::obs::CActionCollection acts;
	acts.insert(act);
	mrpt::obs::CSensoryFrame sf;  // the observation is set on m_pdf
	const bool scoreWalls = m_map && !m_map->empty() && !obs.empty();
	const bool scoreSemantic =
	    m_semantic && !m_semantic->empty() && semantic && !semantic->empty();
	const bool score = scoreWalls || scoreSemantic;
	// The correction needs the map's direction and the sweep's, not its
	// wall samples: a sweep without walls may carry its ground borders'.
	const bool correct = m_map && !m_map->empty() && m_options.mainDirections &&
	                     m_map->mainDirection() && obs.dominantDirection;
	m_pdf.setObservation(&obs);
	m_pdf.setSemantic(
	    scoreSemantic ? m_semantic : nullptr,
	    scoreSemantic ? semantic : nullptr);
	m_pdf.setEffectivePoints(
	    m_global ? m_options.globalEffectivePoints : m_options.effectivePoints);
	m_pdf.setHeadingCorrection(
	    correct ? m_map->mainDirection() : std::nullopt,
	    correct ? obs.dominantDirection : std::nullopt, m_options.headingNoise,
	    m_options.maxCorrection);
	mrpt::bayes::CParticleFilter::TParticleFilterStats stats;
	m_pf.executeOn(m_pdf, &acts, score ? &sf : nullptr, &stats);
	m_pdf.setObservation(nullptr);
	m_pdf.setSemantic(nullptr, nullptr);
	LocalizationUpdate u = summarize(m_pdf, m_options);
	if (m_global && score)
	{
		m_globalUpdates++;
		if (u.converged)
		{
			m_global = false;
			m_convergedAfter = m_globalUpdates;
			logFmt(
			    mrpt::system::LVL_INFO,
			    "global localization converged after %d updates at (%.2f, "
			    "%.2f, %.1f deg), spread %.3f m %.2f deg, %zu particles",
			    m_globalUpdates, u.pose.x(), u.pose.y(),
			    mrpt::RAD2DEG(u.pose.phi()), u.stdXY, mrpt::RAD2DEG(u.stdYaw),
			    u.particles);
		}
	}
	u.headingCorrected = correct;
	u.ms = std::chrono::duration<double, std::milli>(
	           std::chrono::steady_clock::now() - t0)
	           .count();
	if (scoreWalls)
		u.inlierFraction = m_map->inlierFraction(u.pose, obs.samples);

	// Likelihood collapse while tracking in a known map: spread the particles
	// over the free space and score the same sweep again.
	if (scoreWalls && m_freeCount > 0 && m_options.kidnapDetection && !m_global)
	{
		if (u.inlierFraction < m_options.kidnapInlierFraction)
			m_lowInlierUpdates++;
		else
			m_lowInlierUpdates = 0;
		if (m_lowInlierUpdates >= m_options.kidnapUpdates)
		{
			m_kidnappings++;
			logFmt(
			    mrpt::system::LVL_WARN,
			    "kidnapped robot: %.0f%% of wall samples fit at (%.2f, %.2f);"
			    " global relocalization",
			    100 * u.inlierFraction, u.pose.x(), u.pose.y());
			initializeGlobal();
			const double ms = u.ms;
			const bool detect = m_options.kidnapDetection;
			m_options.kidnapDetection = false;
			u = update(mrpt::poses::CPose2D(), obs, semantic);
			m_options.kidnapDetection = detect;
			u.ms += ms;
			u.kidnapped = true;
		}
	}
	return u;
}

void Localizer::translate(double dx, double dy, double dyaw)
{
	for (auto& p : m_pdf.m_particles)
	{
		p.d.x += dx;
		p.d.y += dy;
		p.d.phi = mrpt::math::wrapToPi(p.d.phi + dyaw);
	}
}

mrpt::poses::CPose2D Localizer::pose() const
{
	return summarize(m_pdf, m_options).pose;
}

}  // namespace semnav
