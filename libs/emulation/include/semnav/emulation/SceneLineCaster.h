/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/math/TPose2D.h>
#include <mrpt/poses/CPose3D.h>
#include <semnav/sim/RayCaster.h>
#include <semnav/sim/Scene.h>

#include <cstdint>
#include <vector>

namespace semnav
{
/** True ranges of one scan line of a 2D laser in a scene, cast as
 * TiltingLaserSimulator casts them: beam at bearing b (relative to the
 * scanner's x axis) points along cos(b) x_s + sin(b) y_s of the scanner
 * pose robot + sensorPose. Serves the LMS emulator and the capture check. */
class SceneLineCaster
{
public:
	explicit SceneLineCaster(const Scene& scene, uint64_t seed = 0);

	const Scene& scene() const { return m_scene; }
	const SensorSpec& spec() const { return m_scene.sensor; }

	/** Range per bearing (m); 0 where nothing is hit within maxRange. */
	std::vector<double> cast(
	    const mrpt::math::TPose2D& robot,
	    const mrpt::poses::CPose3D& sensorPose,
	    const std::vector<double>& bearings, double maxRange) const;

private:
	Scene m_scene;
	RayCaster m_caster;
};

}  // namespace semnav
