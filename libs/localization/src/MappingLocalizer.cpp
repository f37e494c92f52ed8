/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <semnav/localization/MappingLocalizer.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/perception/LabeledSweep.h>
#include <semnav/scan/Sweep.h>

#include <chrono>
#include <cmath>

namespace semnav
{
const std::vector<std::string>& MappingLocalizer::TOptions::sections()
{
	static const std::vector<std::string> s = {
	    "WallExtractor",     "WallMap",          "Localizer",
	    "SemanticExtractor", "SemanticEvidence", "ObjectFootprints",
	    "PredictionGuard",   "GroundBorders"};
	return s;
}

void MappingLocalizer::TOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& c, const std::string& prefix)
{
	walls.loadFromConfigFile(c, prefix + "WallExtractor");
	wallMap.loadFromConfigFile(c, prefix + "WallMap");
	localizer.loadFromConfigFile(c, prefix + "Localizer");
	semanticExtractor.loadFromConfigFile(c, prefix + "SemanticExtractor");
	semantic.loadFromConfigFile(c, prefix + "SemanticEvidence");
	footprints.loadFromConfigFile(c, prefix + "ObjectFootprints");
	guard.loadFromConfigFile(c, prefix + "PredictionGuard");
	borders.loadFromConfigFile(c, prefix + "GroundBorders");
}

void MappingLocalizer::TOptions::saveToConfigFile(
    mrpt::config::CConfigFileBase& c, const std::string& prefix) const
{
	walls.saveToConfigFile(c, prefix + "WallExtractor");
	wallMap.saveToConfigFile(c, prefix + "WallMap");
	localizer.saveToConfigFile(c, prefix + "Localizer");
	semanticExtractor.saveToConfigFile(c, prefix + "SemanticExtractor");
	semantic.saveToConfigFile(c, prefix + "SemanticEvidence");
	footprints.saveToConfigFile(c, prefix + "ObjectFootprints");
	guard.saveToConfigFile(c, prefix + "PredictionGuard");
	borders.saveToConfigFile(c, prefix + "GroundBorders");
}

MappingLocalizer::MappingLocalizer(const TOptions& options, Method method)
    : mrpt::system::COutputLogger("MappingLocalizer"),
      m_options(options),
      m_method(method),
      m_extractor(options.walls),
      m_walls(options.wallMap),
      m_localizer(options.localizer),
      m_stock(options.localizer),
      m_semanticExtractor(options.semanticExtractor),
      m_semantic(options.semantic),
      m_footprints(options.footprints),
      m_guard(options.guard),
      m_borders(options.borders)
{
	m_localizer.setWallMap(&m_walls);
	m_localizer.setSemanticMap(&m_semantic);
	if (options.footprints.enabled()) m_semantic.setFootprints(&m_footprints);
}

LocalizationUpdate MappingLocalizer::localizeWalls(
    const mrpt::poses::CPose2D& incr, const LabeledSweep& labeled)
{
	// The prediction: the last estimate moved by the increment, with the
	// particles' spread and the motion model's noise.
	mrpt::obs::CActionRobotMovement2D act;
	act.computeFromOdometry(
	    incr, Localizer::motionOptions(m_options.localizer));
	mrpt::poses::CPosePDFGaussian step;
	step.copyFrom(*act.poseChange);
	const auto prior = m_localizer.pdf().getCovarianceAndMean();
	const mrpt::poses::CPosePDFGaussian predicted = PredictionGuard::predict(
	    mrpt::poses::CPosePDFGaussian(m_pose, std::get<0>(prior)), step);
	// A sweep without a wall direction: its ground borders' direction, when
	// it moves the predicted heading by little (a diagonal path is no main
	// direction).
	bool fromBorders = false;
	if (m_borderDirection && m_walls.mainDirection())
	{
		const double d = MainDirections::correction(
		    predicted.mean.phi(), *m_borderDirection, *m_walls.mainDirection());
		if (std::abs(d) <= m_options.borders.maxCorrection)
			m_obs.dominantDirection = m_borderDirection, fromBorders = true;
	}
	m_semanticObs = SemanticObservation();
	if (!m_semantic.empty())
	{
		const auto& p = predicted.mean;
		m_semanticObs = m_semantic.observedPart(
		    p.x(), p.y(), p.phi(), m_semanticExtractor.extract(labeled));
		if (m_options.footprints.enabled())
			m_semanticObs.footprints = m_footprints.observedPart(
			    p.x(), p.y(), p.phi(), m_sweepFootprints);
	}
	LocalizationUpdate u = m_localizer.update(incr, m_obs, &m_semanticObs);
	u.headingFromBorders = fromBorders && u.headingCorrected;
	auto [cov, mean] = m_localizer.pdf().getCovarianceAndMean();
	// Several hypotheses: the sweep told them apart rather than leaving a
	// direction free; test the estimate's hypothesis alone.
	const PredictionGuard::Hypothesis h =
	    m_guard.hypothesisOf(m_localizer.pdf(), u.pose);
	if (h.weight < m_options.guard.unimodalWeight) cov = h.cov, mean = h.mean;
	const PredictionGuard::Result g = m_guard.apply(predicted, mean, cov);
	u.unconstrained = g.unconstrained;
	u.varianceRatio = g.maxVarianceRatio;
	if (m_options.guard.enabled)
	{
		m_localizer.translate(g.shiftX, g.shiftY, g.shiftYaw);
		u.pose = g.pose;
	}
	return u;
}

void MappingLocalizer::updateSemanticMap(const SemanticMap& map)
{
	if (!m_options.semantic.enabled()) return;
	const auto t0 = std::chrono::steady_clock::now();
	m_semantic.update(map, m_options.semantic.mappingFlatLabelsOnly);
	m_semanticMs = std::chrono::duration<double, std::milli>(
	                   std::chrono::steady_clock::now() - t0)
	                   .count();
}

mrpt::poses::CPose2D MappingLocalizer::process(
    const Sweep& sweep, const LabeledSweep& labeled, SemanticMap& map)
{
	const mrpt::poses::CPose2D odo = sweep.odometry();
	m_obs = m_extractor.extract(labeled);
	m_sweepFootprints.clear();
	m_borderDirection.reset();
	if (m_method == Method::Walls && m_options.borders.enabled &&
	    !m_obs.dominantDirection)
		m_borderDirection = m_borders.direction(labeled);
	if (m_method == Method::Walls && m_options.footprints.enabled())
		m_sweepFootprints = m_footprints.extract(labeled);
	mrpt::poses::CPose2D pose = odo;
	m_last = LocalizationUpdate();
	m_last.converged = true;
	if (!m_started)
	{
		m_localizer.initialize(pose);
		m_stock.initialize(pose);
		m_started = true;
		m_last.pose = pose;
	}
	else
	{
		const mrpt::poses::CPose2D incr = odo - m_lastOdometry;
		switch (m_method)
		{
			case Method::Odometry:
				m_last.pose = pose;
				break;
			case Method::Walls:
				m_last = localizeWalls(incr, labeled);
				pose = m_last.pose;
				break;
			case Method::OccupancyMcl:
				m_stock.setMap(OccupancyMcl::mrptGrid(map));
				m_last =
				    m_stock.update(incr, OccupancyMcl::horizontalScan(sweep));
				pose = m_last.pose;
				break;
		}
	}
	map.insert(sweep, labeled, pose);
	if (m_method == Method::Walls)
	{
		m_walls.addObservation(m_obs.segments, pose);
		m_walls.update(map);
		updateSemanticMap(map);
		m_footprints.insert(m_sweepFootprints, pose);
	}
	m_lastOdometry = odo;
	m_pose = pose;
	return pose;
}

}  // namespace semnav
