/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/math/TPoint2D.h>
#include <semnav/common/GridGeometry.h>
#include <semnav/common/Label.h>
#include <semnav/map/SemanticMap.h>

#include <opencv2/core/mat.hpp>
#include <vector>

namespace semnav
{
/** Draws a SemanticMap like the paper's Fig. 4: white free floor (unknown
 * cells light grey, where the paper has white too), black walls and other
 * obstacles, the colours of the ClassRegistry's area classes (sidewalk,
 * grass) and of its instance classes' objects (door, stairs, washbasin,
 * wastebasket, ...), north (+y) up, with a legend and a 1 m scale bar. */
class MapRenderer
{
public:
	/** BGR image; each cell is `pixelsPerCell` pixels wide. */
	static cv::Mat render(const SemanticMap& map, int pixelsPerCell = 3);
	/** BGR colour of a label in renderings (its registry mapColour; white
	 * for an id that is not registered). */
	static cv::Scalar labelColor(Label l);
	/** The pixel of world point (x, y) in a render() of a map of geometry
	 * `g` at `pixelsPerCell`. */
	static cv::Point pixel(
	    const GridGeometry& g, int pixelsPerCell, double x, double y);
	/** Draws a world-frame polyline over such a rendering. */
	static void polyline(
	    cv::Mat& img, const GridGeometry& g, int pixelsPerCell,
	    const std::vector<mrpt::math::TPoint2D>& pts, const cv::Scalar& color,
	    int width);
};

}  // namespace semnav
