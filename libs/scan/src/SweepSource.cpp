/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/scan/SweepSource.h>

namespace semnav
{
const char* SweepSource::endName(End e)
{
	switch (e)
	{
		case End::None:
			return "none";
		case End::EndOfLog:
			return "end of log";
		case End::DeviceLost:
			return "device lost";
		case End::Cancelled:
			return "cancelled";
	}
	return "?";
}

}  // namespace semnav
