/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/common/Error.h>

namespace semnav
{
/** Base of the errors of the navigation module. */
class NavigationError : public Error
{
	using Error::Error;
};

/** A navigation command that is not one of the accepted forms. */
class NavCommandError : public NavigationError
{
	using NavigationError::NavigationError;
};

}  // namespace semnav
