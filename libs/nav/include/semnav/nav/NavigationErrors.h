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

/** The robot could not localize itself in the map (semnav-nav
 * --localize): no convergence within the allowed sweeps, or nothing to
 * localize against. */
class LocalizationFailedError : public NavigationError
{
	using NavigationError::NavigationError;
};

}  // namespace semnav
