/* semnav: semantic navigation from tilting-laser sweeps */
// Entry point of libsemnav_hwdrivers.so: registers the semnav sensors with
// MRPT's CGenericSensor factory when rawlog-grabber loads the plugin (-p).
#include <semnav/hwdrivers/CTiltingLMS2xx.h>

namespace
{
struct RegisterSemnavSensors
{
	RegisterSemnavSensors()
	{
		semnav::CTiltingLMS2xx::doRegister();
		semnav::CTiltingLMS2xx::exitNonZeroOnStartupError();
	}
};
const RegisterSemnavSensors registerSemnavSensors;
}  // namespace
