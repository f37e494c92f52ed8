/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/AtomicFile.h>
#include <semnav/map/MapIO.h>
#include <semnav/navsim/NavigationRenderer.h>
#include <semnav/navsim/NavigationRun.h>
#include <semnav/navsim/SceneMapBuilder.h>
#include <semnav/planning/PlanningErrors.h>
#include <semnav/planning/SemanticPlanner.h>
#include <semnav/sim/SceneLoader.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <opencv2/imgcodecs.hpp>

namespace semnav
{
NavigationRun::NavigationRun(const Settings& settings)
    : m_settings(settings),
      m_scene(SceneLoader::loadFile(settings.scene)),
      m_map(settings.config.map)
{
	if (!m_settings.gtMapScene.empty())
		SceneMapBuilder::build(
		    SceneLoader::loadFile(m_settings.gtMapScene), m_map);
	else
		MapIO::load(m_settings.mapDir, m_map);
	for (const auto& name : m_settings.instancesFromScene)
	{
		const Label l = labelFromName(name);
		if (m_map.instances(l).empty() &&
		    SceneMapBuilder::addInstances(m_scene, l, m_map) > 0)
			m_added.push_back(name);
	}
	if (!m_settings.outDir.empty())
	{
		createDirectories(m_settings.outDir);
		const std::filesystem::path dir(m_settings.outDir);
		m_navlog = (dir / "navigation.reactivenavlog").string();
		m_png = (dir / "navigation.png").string();
	}
}

NavigationRun::~NavigationRun() = default;

SimulatedNavigation::Result NavigationRun::run(
    const NavCommand& command, const mrpt::math::TPose2D& start)
{
	SimulatedNavigation sim(m_map, m_scene, m_settings.config);
	if (m_settings.kidnapAt)
		sim.setKidnapping(*m_settings.kidnapAt, m_settings.kidnapTo);
	if (m_settings.localize)
		sim.setLocalization(
		    *m_settings.localize, m_settings.localization,
		    m_settings.perception, m_settings.startGuess, m_settings.cascades);
	if (m_settings.verbose && sim.localizer())
	{
		// Progress on stderr (MRPT's console output is stdout, which may
		// carry JSON).
		auto& log = *sim.localizer();
		log.setMinLoggingLevel(mrpt::system::LVL_INFO);
		log.logging_enable_console_output = false;
		log.logRegisterCallback(
		    [](std::string_view msg, mrpt::system::VerbosityLevel,
		       std::string_view loggerName, mrpt::Clock::time_point)
		    { std::cerr << loggerName << ": " << msg << std::endl; });
	}
	const auto r = sim.run(command, start, m_navlog);
	if (!m_png.empty())
	{
		std::vector<uchar> buf;
		cv::imencode(".png", NavigationRenderer::render(m_map, r), buf);
		writeFileAtomically(m_png, std::string(buf.begin(), buf.end()));
	}
	return r;
}

std::vector<NavigationRun::InstanceCost> NavigationRun::instanceCosts(
    const NavCommand& command, const mrpt::math::TPose2D& start) const
{
	std::vector<InstanceCost> out;
	if (command.kind != NavCommand::Kind::NearestLabel) return out;
	const auto& config = m_settings.config;
	const SemanticPlanner planner(m_map, config.cnn, config.traversability);
	const CostProfile profile = config.navigationProfile();
	for (const auto& o : m_map.instances(command.label))
	{
		InstanceCost c;
		c.id = o.id;
		c.euclidean =
		    std::hypot(o.centroid.x - start.x, o.centroid.y - start.y);
		try
		{
			c.cost =
			    planner.toObject(start.x, start.y, o.id, profile).path.cost;
		}
		catch (const PlanningError&)
		{
		}
		out.push_back(c);
	}
	return out;
}
}  // namespace semnav
