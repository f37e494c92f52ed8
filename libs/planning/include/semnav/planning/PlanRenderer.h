/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/planning/SemanticPlanner.h>

#include <opencv2/core/mat.hpp>

namespace semnav
{
/** Pictures of a plan, north (+y) up, three panels side by side: the map
 * (MapRenderer) with the goal cells and the path, the traversability u
 * (blocked black, free white, costly cells shaded) and the diffusion field
 * (cost-to-go, colour-mapped; unreachable black) with the path. */
class PlanRenderer
{
public:
	static cv::Mat render(
	    const SemanticMap& map, const SemanticPlanner::Plan& plan,
	    int pixelsPerCell = 3);
};

}  // namespace semnav
