/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/navsim/SimulatedNavigation.h>

#include <opencv2/core/mat.hpp>

namespace semnav
{
class SemanticMap;

/** Picture of a navigation run over the map (MapRenderer, north up):
 * earlier plans thin orange, the last plan red with its waypoints, the
 * driven trajectory blue, start green (heading line), end blue, with
 * localization the navigator's belief thin teal and the localized start a
 * teal ring with heading, the reached object ringed,
 * sensed obstacles the map lacked purple, collisions magenta crosses, and a
 * one-line summary. */
class NavigationRenderer
{
public:
	static cv::Mat render(
	    const SemanticMap& map, const SimulatedNavigation::Result& result,
	    int pixelsPerCell = 4);
};

}  // namespace semnav
