/* semnav: semantic navigation from tilting-laser sweeps */
// SemanticMap::insert(), the views of the objects: which instances a sweep
// had in view (countViews(), doorInView()), the door views counted in the
// sweeps kept (countDoorViews(), keepSweep()), the doors' normals.
#include <mrpt/poses/CPose3D.h>
#include <semnav/common/ClassRegistry.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/map/SweepView.h>
#include <semnav/scan/Sweep.h>

#include <algorithm>
#include <cmath>

namespace semnav
{
/** A sweep kept to count door views after it (countDoorViews()). */
struct SemanticMap::PastSweep
{
	Sweep sweep;
	mrpt::poses::CPose3D robot;
};

void SemanticMap::addNormal(
    const mrpt::poses::CPose3D& robot, const mrpt::math::TPoint3D& normal,
    ObjectInstance& o)
{
	const double yaw = robot.yaw();
	double nx = std::cos(yaw) * normal.x - std::sin(yaw) * normal.y,
	       ny = std::sin(yaw) * normal.x + std::cos(yaw) * normal.y;
	const double n = std::hypot(nx, ny);
	if (n < 1e-6) return;
	nx /= n;
	ny /= n;
	if (nx * o.normalSum.x + ny * o.normalSum.y < 0)
	{
		nx = -nx;
		ny = -ny;
	}
	o.normalSum.x += nx;
	o.normalSum.y += ny;
}

void SemanticMap::countViews(
    const Sweep& sweep, const mrpt::poses::CPose3D& robot,
    std::vector<int>& viewedThisSweep)
{
	const SweepView view(
	    sweep, m_options.viewMaxBearingDeg * M_PI / 180,
	    m_options.viewMinPixels);
	// Region classes (doors): door views (the rules find no door beside
	// the robot, nor one half behind a corner).
	const LabelSet fromRegions = ClassRegistry::instance().select(
	    [](const ClassInfo& c)
	    { return c.instances == ClassInfo::InstanceSource::Regions; });
	for (auto& o : m_instances)
	{
		if (fromRegions.contains(o.label))
		{
			if (!doorInView(sweep, robot, o)) continue;
		}
		else
		{
			mrpt::math::TPoint3D p;
			robot.inverseComposePoint(o.centroid, p);
			if (!view.sees(p, o.typicalSize())) continue;
		}
		o.views++;
		viewedThisSweep.push_back(o.id);
	}
}

bool SemanticMap::doorInView(
    const Sweep& sweep, const mrpt::poses::CPose3D& robot,
    const ObjectInstance& o) const
{
	const SweepView view(
	    sweep, m_options.doorViewMaxBearingDeg * M_PI / 180,
	    m_options.doorViewMinPixels);
	mrpt::math::TPoint3D p;
	robot.inverseComposePoint(o.centroid, p);
	mrpt::math::TPoint3D size = o.typicalSize();
	const double nx = o.normalSum.x, ny = o.normalSum.y;
	const double nn = std::hypot(nx, ny);
	if (nn > 1e-9 && !sweep.empty())
	{
		// Foreshortened: the door's width across the line of sight.
		const auto& axis = sweep.sensorPose(sweep.rows() / 2);
		const double lx = p.x - axis.x(), ly = p.y - axis.y();
		const double ln = std::max(std::hypot(lx, ly), 1e-9);
		const double yaw = robot.yaw();
		const double rx = std::cos(yaw) * nx + std::sin(yaw) * ny,
		             ry = -std::sin(yaw) * nx + std::cos(yaw) * ny;
		const double cosInc = std::abs(rx * lx + ry * ly) / (nn * ln);
		if (cosInc <
		    std::cos(m_options.doorViewMaxIncidenceDeg * M_PI / 180) - 1e-9)
			return false;
		size.x *= cosInc;
	}
	return view.visibleShare(p, size) >=
	       m_options.doorViewMinVisibleShare - 1e-9;
}

void SemanticMap::countDoorViews(
    std::size_t firstNew, const std::vector<int>& seenThisSweep,
    std::vector<int>& viewedThisSweep)
{
	for (std::size_t k = 0; k < m_instances.size(); k++)
	{
		ObjectInstance& o = m_instances[k];
		if (classInfo(o.label).instances != ClassInfo::InstanceSource::Regions)
			continue;
		if (k >= firstNew)
			for (const auto& past : m_pastSweeps)
				if (doorInView(past->sweep, past->robot, o)) o.views++;
		if (std::find(seenThisSweep.begin(), seenThisSweep.end(), o.id) !=
		    seenThisSweep.end())
			countDetectedView(o, viewedThisSweep);
	}
}

ObjectInstance* SemanticMap::instanceWithId(int id)
{
	for (auto& o : m_instances)
		if (o.id == id) return &o;
	return nullptr;
}

void SemanticMap::countDetectedView(
    ObjectInstance& o, std::vector<int>& viewedThisSweep)
{
	if (std::find(viewedThisSweep.begin(), viewedThisSweep.end(), o.id) !=
	    viewedThisSweep.end())
		return;
	o.views++;
	viewedThisSweep.push_back(o.id);
}

void SemanticMap::keepSweep(
    const Sweep& sweep, const mrpt::poses::CPose3D& robot)
{
	if (m_options.doorViewHistory <= 0) return;
	m_pastSweeps.push_back(
	    std::make_shared<const PastSweep>(PastSweep{sweep, robot}));
	while (m_pastSweeps.size() >
	       static_cast<std::size_t>(m_options.doorViewHistory))
		m_pastSweeps.pop_front();
}

}  // namespace semnav
