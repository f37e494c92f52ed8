/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/emulation/SceneLineCaster.h>

#include <cmath>

namespace semnav
{
SceneLineCaster::SceneLineCaster(const Scene& scene, uint64_t seed)
    : m_scene(scene), m_caster(m_scene, seed)
{
}

std::vector<double> SceneLineCaster::cast(
    const mrpt::math::TPose2D& robot, const mrpt::poses::CPose3D& sensorPose,
    const std::vector<double>& bearings, double maxRange) const
{
	const mrpt::poses::CPose3D r(robot.x, robot.y, 0, robot.phi, 0, 0);
	const mrpt::poses::CPose3D world = r + sensorPose;
	const auto& R = world.getRotationMatrix();
	const mrpt::math::TPoint3D o(world.x(), world.y(), world.z());
	std::vector<double> out(bearings.size(), 0.0);
	for (std::size_t c = 0; c < bearings.size(); c++)
	{
		const double cp = std::cos(bearings[c]), sp = std::sin(bearings[c]);
		const mrpt::math::TPoint3D d(
		    cp * R(0, 0) + sp * R(0, 1), cp * R(1, 0) + sp * R(1, 1),
		    cp * R(2, 0) + sp * R(2, 1));
		const RayHit h = m_caster.cast(o, d, maxRange);
		if (h.hit) out[c] = h.range;
	}
	return out;
}

}  // namespace semnav
