/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/core/bits_math.h>
#include <semnav/emulation/TiltingScannerEmulator.h>
#include <semnav/sim/Scene.h>

#include <cmath>

namespace semnav
{
namespace
{
long tiltLimit()
{
	return std::lround(
	    mrpt::DEG2RAD(100.0) / TiltingScannerEmulator::tiltResolution());
}
}  // namespace

double TiltingScannerEmulator::tiltResolution()
{
	return mrpt::DEG2RAD(PtuEmulator::kArcSecPerPosition / 3600.0);
}

LmsEmulator::Options TiltingScannerEmulator::withScene(
    LmsEmulator::Options o, const Scene& scene)
{
	o.rangeNoise = scene.sensor.rangeNoise;
	o.maxRange = scene.sensor.maxRange;
	return o;
}

TiltingScannerEmulator::TiltingScannerEmulator(
    const Scene& scene, LmsEmulator::Options lms, const std::string& ptuLink)
    : m_caster(scene),
      m_head(tiltResolution(), -tiltLimit(), tiltLimit()),
      m_lms(m_caster, m_head, withScene(lms, scene)),
      m_ptu(m_head, ptuLink)
{
}

TiltingScannerEmulator::~TiltingScannerEmulator() = default;

void TiltingScannerEmulator::start()
{
	m_lms.start();
	m_ptu.start();
}

void TiltingScannerEmulator::stop()
{
	m_ptu.stop();
	m_lms.stop();
}
}  // namespace semnav
