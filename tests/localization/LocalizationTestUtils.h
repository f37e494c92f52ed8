/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/localization/WallExtractor.h>
#include <semnav/localization/WallSegment.h>

#include <vector>

namespace semnav::test
{
inline WallSegment seg(double x0, double y0, double x1, double y1)
{
	WallSegment s;
	s.p0 = {x0, y0};
	s.p1 = {x1, y1};
	return s;
}

/** A 10 m x 6 m room with an inner wall stub and a pillar (world frame). */
inline std::vector<WallSegment> roomWalls()
{
	return {seg(0, 0, 10, 0),  seg(10, 0, 10, 6),   seg(10, 6, 0, 6),
	        seg(0, 6, 0, 0),   seg(6, 0, 6, 2.5),   seg(3, 4, 4, 4),
	        seg(4, 4, 4, 4.6), seg(4, 4.6, 3, 4.6), seg(3, 4.6, 3, 4)};
}

/** What a robot at `pose` sees of the walls (all of them, clipped to
 * `range` around it by dropping far segments), in its frame, finished by
 * the extractor (samples, dominant direction). */
inline WallObservation observe(
    const std::vector<WallSegment>& world, const mrpt::poses::CPose2D& pose,
    const WallExtractor& ex = WallExtractor(), double range = 8.0)
{
	WallObservation obs;
	const mrpt::poses::CPose2D inv = -pose;
	for (const auto& s : world)
	{
		const auto mid = (s.p0 + s.p1) * 0.5;
		if (std::hypot(mid.x - pose.x(), mid.y - pose.y()) > range) continue;
		obs.segments.push_back(s.transformed(inv));
	}
	ex.finish(obs);
	return obs;
}
}  // namespace semnav::test
