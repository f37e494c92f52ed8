/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/localization/MappingLocalizer.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/perception/LabeledSweep.h>
#include <semnav/scan/Sweep.h>

namespace semnav
{
const std::vector<std::string>& MappingLocalizer::TOptions::sections()
{
	static const std::vector<std::string> s = {
	    "WallExtractor", "WallMap", "Localizer", "SemanticExtractor",
	    "SemanticEvidence"};
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
}

void MappingLocalizer::TOptions::saveToConfigFile(
    mrpt::config::CConfigFileBase& c, const std::string& prefix) const
{
	walls.saveToConfigFile(c, prefix + "WallExtractor");
	wallMap.saveToConfigFile(c, prefix + "WallMap");
	localizer.saveToConfigFile(c, prefix + "Localizer");
	semanticExtractor.saveToConfigFile(c, prefix + "SemanticExtractor");
	semantic.saveToConfigFile(c, prefix + "SemanticEvidence");
}

MappingLocalizer::MappingLocalizer(const TOptions& options, Method method)
    : mrpt::system::COutputLogger("MappingLocalizer"),
      m_options(options),
      m_method(method),
      m_extractor(options.walls),
      m_walls(options.wallMap),
      m_localizer(options.localizer),
      m_stock(options.localizer)
{
	m_localizer.setWallMap(&m_walls);
}

mrpt::poses::CPose2D MappingLocalizer::process(
    const Sweep& sweep, const LabeledSweep& labeled, SemanticMap& map)
{
	const mrpt::poses::CPose2D odo = sweep.odometry();
	m_obs = m_extractor.extract(labeled);
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
				m_last = m_localizer.update(incr, m_obs);
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
		m_walls.rebuild(&map);
	}
	m_lastOdometry = odo;
	m_pose = pose;
	return pose;
}

}  // namespace semnav
