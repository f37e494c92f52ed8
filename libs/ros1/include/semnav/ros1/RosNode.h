/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <string>

namespace semnav
{
/** Starts roscpp in this process once (node `name`, no SIGINT handler, no
 * rosout) and waits up to `masterTimeout` s for the master of
 * ROS_MASTER_URI; throws IoError naming the master when it does not
 * answer. Later calls (any name) only wait for the master. Calls to a
 * master that goes away later give up after 1 s instead of hanging. */
void startRosNode(const std::string& name, double masterTimeout);

}  // namespace semnav
