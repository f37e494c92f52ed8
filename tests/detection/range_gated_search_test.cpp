/* semnav: semantic navigation from tilting-laser sweeps */
/* The range-gated search's pieces on their own
 * (libs/detection/src/RangeGatedSearch.h). */
#include <gtest/gtest.h>
#include <semnav/cascade/RangeGate.h>

#include <cmath>
#include <limits>

#include "../../libs/detection/src/RangeGatedSearch.h"

using semnav::RangeGate;
using semnav::detail::GateBounds;

namespace
{
/** Ranges around each bound of `b` (a few floats either side) and spread
 * over 0..20 m. */
std::vector<float> probes(const GateBounds& b)
{
	std::vector<float> r;
	for (float edge : {b.lo, b.loCut, b.hi, b.cut})
	{
		if (!std::isfinite(edge)) continue;
		float x = edge;
		for (int k = 0; k < 4; k++) x = std::nextafter(x, 0.f);
		for (int k = 0; k < 9; k++, x = std::nextafter(x, 1e9f)) r.push_back(x);
	}
	for (float x = 0; x < 20; x += 0.0137f) r.push_back(x);
	return r;
}
}  // namespace

TEST(RangeGatedSearch, GateBoundsDecideAsTheGate)
{
	RangeGate g;
	g.perSide = 0.0031;  // rad per pixel
	g.lo = 0.21;
	g.loCut = 0.12;
	g.hi = 0.63;
	g.cutRange = 1.7;
	int accepted = 0, refused = 0;
	for (double side : {24.0, 31.0, 57.0, 113.0})
	{
		const GateBounds b(g, side);
		for (float r : probes(b))
		{
			ASSERT_EQ(b.accepts(r), g.accepts(r, side))
			    << "range " << r << " side " << side;
			(g.accepts(r, side) ? accepted : refused)++;
		}
	}
	// Both decisions were exercised.
	EXPECT_GT(accepted, 20);
	EXPECT_GT(refused, 20);
}

TEST(RangeGatedSearch, GateBoundsRefuseNoRange)
{
	RangeGate g;
	g.lo = 0;
	g.loCut = 0;
	const GateBounds b(g, 24);
	EXPECT_FALSE(b.accepts(0.f));
	EXPECT_FALSE(b.accepts(std::numeric_limits<float>::infinity()));
}
