/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/emulation/LmsEmulator.h>
#include <semnav/emulation/PtuEmulator.h>
#include <semnav/emulation/SceneLineCaster.h>
#include <semnav/hwdrivers/TiltHeadModel.h>

#include <string>

namespace semnav
{
struct Scene;

/** The emulated tilting scanner of semnav-device-emulator: a SICK LMS200
 * and a Directed Perception PTU on pseudo-terminals sharing one tilt head
 * (the PTU's resolution, +-100 deg), the LMS scanning `scene` from the
 * robot pose of its options (fixed, or the moving base's through
 * poseSource) with the scene's range noise and maximum range. */
class TiltingScannerEmulator
{
public:
	/** `lms`: the LMS's options (its range noise and maximum range are
	 * taken from the scene); `ptuLink`: symlink kept pointing at the PTU's
	 * terminal ("" for none). */
	TiltingScannerEmulator(
	    const Scene& scene, LmsEmulator::Options lms,
	    const std::string& ptuLink);
	~TiltingScannerEmulator();

	/** Opens both terminals and starts serving; throws IoError. */
	void start();
	/** Stops both devices (the PTU first). */
	void stop();

	const LmsEmulator& lms() const { return m_lms; }
	const PtuEmulator& ptu() const { return m_ptu; }

	/** The tilt resolution of the emulated PTU (rad per position). */
	static double tiltResolution();

private:
	static LmsEmulator::Options withScene(
	    LmsEmulator::Options o, const Scene& scene);

	SceneLineCaster m_caster;
	TiltHeadModel m_head;
	LmsEmulator m_lms;
	PtuEmulator m_ptu;
};

}  // namespace semnav
