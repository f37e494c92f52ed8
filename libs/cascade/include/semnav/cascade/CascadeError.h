/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/common/Error.h>

namespace semnav
{
/** A cascade file is unreadable, not valid XML, or not a stump-based HAAR
 * BOOST cascade; or training input is unusable (no positives, no negative
 * windows). The message names the file and what is wrong. */
class CascadeError : public Error
{
	using Error::Error;
};

}  // namespace semnav
