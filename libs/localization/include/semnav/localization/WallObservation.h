/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/math/TPoint2D.h>
#include <semnav/localization/WallSegment.h>

#include <cstddef>
#include <optional>
#include <vector>

namespace semnav
{
/** The walls of one sweep in the robot frame: what the particle filter
 * scores (WallExtractor builds it). */
struct WallObservation
{
	std::size_t sweepIndex = 0;
	std::vector<WallSegment> segments;
	/** Points sampled along the segments, the likelihood's input. */
	std::vector<mrpt::math::TPoint2D> samples;
	/** The sweep's dominant wall direction modulo 90 deg (rad, in
	 * [-pi/4, pi/4)), when its walls agree on one (MainDirections). */
	std::optional<double> dominantDirection;

	bool empty() const { return samples.empty(); }
};

}  // namespace semnav
