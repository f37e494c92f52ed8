/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/sim/Scene.h>

#include <cmath>

namespace semnav
{
namespace
{
std::size_t sampleCount(double lo, double hi, double step)
{
	if (!(step > 0) || !(hi >= lo)) return 0;
	return static_cast<std::size_t>(std::llround((hi - lo) / step)) + 1;
}
}  // namespace

std::size_t SensorSpec::beamCount() const
{
	return sampleCount(phiMin, phiMax, phiStep);
}

std::size_t SensorSpec::lineCount() const
{
	return sampleCount(thetaMin, thetaMax, thetaStep);
}

}  // namespace semnav
