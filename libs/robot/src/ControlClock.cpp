/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/robot/ControlClock.h>

#include <chrono>
#include <thread>

namespace semnav
{
double RealTimeClock::now() const
{
	return std::chrono::duration<double>(
	           std::chrono::steady_clock::now().time_since_epoch())
	    .count();
}

void RealTimeClock::waitFor(double seconds)
{
	if (seconds > 0)
		std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
}

}  // namespace semnav
