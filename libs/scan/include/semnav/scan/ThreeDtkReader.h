/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/poses/CPose3D.h>
#include <semnav/scan/Sweep.h>

#include <string>

namespace semnav
{
/** Reads 3DTK "uos" scans (`scanNNN.3d` + `scanNNN.pose`) of a nodding
 * LMS200 into a Sweep.
 *
 * The .3d file is organized: `rows` scan lines of `cols` beams, one
 * `x y z` point per line in centimetres, left-handed sensor frame
 * (x right, y up, z forward). Per pixel r = |p|; row tilt theta = median of
 * atan2(y, z) over the row's valid beams; beam c has phi = -90 deg + c *
 * beam_step. Readings at the no-return code or closer than min_range are
 * invalid. Rows are ordered by increasing tilt as every Sweep. */
class ThreeDtkReader
{
public:
	struct TOptions : public mrpt::config::CLoadableOptions
	{
		void loadFromConfigFile(
		    const mrpt::config::CConfigFileBase& c,
		    const std::string& section) override;
		void saveToConfigFile(
		    mrpt::config::CConfigFileBase& c,
		    const std::string& section) const override;

		std::size_t cols = 360;
		double beamStep = 0.5 * M_PI / 180;
		/** Readings at or beyond this range are "no return" (m). */
		double noReturnRange = 32.7;
		/** Readings closer than this are the robot itself (m). */
		double minRange = 0.5;
		/** LMS200 maximum useful range, stored in the Sweep (m). */
		double maxRange = 32.0;
	};

	ThreeDtkReader();
	explicit ThreeDtkReader(const TOptions& options);

	/** Reads a .3d file; throws IoError for a missing or malformed file
	 * (naming the line). The pose file next to it (same stem, .pose), if
	 * present, sets the sweep's odometry. */
	Sweep read(const std::string& path) const;

	/** Reads a .pose file as a pose in semnav's right-handed world frame
	 * (x forward, y left, z up; metres, radians). */
	static mrpt::poses::CPose3D readPose(const std::string& path);

	/** The pose file of the scan `scanPath`: same stem, `.pose`. */
	static std::string posePath(const std::string& scanPath);

private:
	TOptions m_options;
};

}  // namespace semnav
