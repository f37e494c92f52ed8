/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/ClassRegistry.h>
#include <semnav/map/MapRenderer.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

namespace semnav
{
namespace
{
cv::Scalar bgr(const ClassInfo::Rgb& c)
{
	return {double(c.b), double(c.g), double(c.r)};
}

/** The colour of the area class drawn on a cell (the lowest id wins), if
 * any. */
bool areaColour(const LabelSet& ls, cv::Scalar& col)
{
	for (Label l : allLabels())
	{
		const ClassInfo& c = classInfo(l);
		if (c.mapStyle != ClassInfo::MapStyle::Area || !ls.contains(l))
			continue;
		col = bgr(c.mapColour);
		return true;
	}
	return false;
}

/** Legend rows: the fixed ones, then instance classes and area classes in
 * id order. */
std::vector<std::pair<std::string, cv::Scalar>> legendItems()
{
	std::vector<std::pair<std::string, cv::Scalar>> items = {
	    {"free floor", {255, 255, 255}},
	    {"unknown", {225, 225, 225}},
	    {"wall / obstacle", {0, 0, 0}}};
	for (const auto style :
	     {ClassInfo::MapStyle::Instance, ClassInfo::MapStyle::Area})
		for (Label l : allLabels())
			if (classInfo(l).mapStyle == style)
				items.emplace_back(labelName(l), MapRenderer::labelColor(l));
	return items;
}
}  // namespace

cv::Scalar MapRenderer::labelColor(Label l)
{
	if (!ClassRegistry::instance().contains(l)) return {255, 255, 255};
	return bgr(classInfo(l).mapColour);
}

cv::Mat MapRenderer::render(const SemanticMap& map, int k)
{
	const GridGeometry& g = map.geometry();
	const int legendW = 150;
	const int w = std::max(1, g.cols) * k, h = std::max(1, g.rows) * k;
	cv::Mat img(
	    std::max(h, 180), w + legendW, CV_8UC3, cv::Scalar(255, 255, 255));
	for (int cy = 0; cy < g.rows; cy++)
		for (int cx = 0; cx < g.cols; cx++)
		{
			// The paper draws unknown white too; a light grey tells them apart.
			cv::Scalar col =
			    map.cellState(cx, cy) == SemanticMap::CellState::Unknown
			        ? cv::Scalar(225, 225, 225)
			        : cv::Scalar(255, 255, 255);
			const LabelSet ls = map.labels(cx, cy);
			areaColour(ls, col);
			if (map.cellState(cx, cy) == SemanticMap::CellState::Occupied)
				col = {0, 0, 0};
			const int id = map.objectId(cx, cy);
			if (id > 0 && map.reported(map.instance(id)))
				col = labelColor(map.instance(id).label);
			const int row = (g.rows - 1 - cy) * k;  // +y up
			cv::rectangle(img, cv::Rect(cx * k, row, k, k), col, cv::FILLED);
		}
	// Legend and 1 m scale bar.
	const int x0 = w + 10;
	int y = 20;
	cv::putText(
	    img, "semnav map", {x0, y}, cv::FONT_HERSHEY_SIMPLEX, 0.45, {0, 0, 0},
	    1, cv::LINE_AA);
	for (const auto& [name, col] : legendItems())
	{
		y += 18;
		cv::rectangle(img, cv::Rect(x0, y - 10, 12, 12), col, cv::FILLED);
		cv::rectangle(img, cv::Rect(x0, y - 10, 12, 12), {0, 0, 0}, 1);
		cv::putText(
		    img, name, {x0 + 18, y}, cv::FONT_HERSHEY_SIMPLEX, 0.4, {0, 0, 0},
		    1, cv::LINE_AA);
	}
	y += 25;
	const int bar = static_cast<int>(std::round(k / g.resolution));
	cv::line(img, {x0, y}, {x0 + bar, y}, {0, 0, 0}, 2);
	cv::putText(
	    img, "1 m", {x0 + bar + 5, y + 4}, cv::FONT_HERSHEY_SIMPLEX, 0.4,
	    {0, 0, 0}, 1, cv::LINE_AA);
	return img;
}

cv::Point MapRenderer::pixel(const GridGeometry& g, int k, double x, double y)
{
	const double col = (x - g.originX) / g.resolution;
	const double row = (y - g.originY) / g.resolution;
	return {
	    static_cast<int>(std::lround(col * k)),
	    static_cast<int>(std::lround((g.rows - row) * k))};
}

void MapRenderer::polyline(
    cv::Mat& img, const GridGeometry& g, int k,
    const std::vector<mrpt::math::TPoint2D>& pts, const cv::Scalar& c, int w)
{
	for (std::size_t i = 1; i < pts.size(); i++)
		cv::line(
		    img, pixel(g, k, pts[i - 1].x, pts[i - 1].y),
		    pixel(g, k, pts[i].x, pts[i].y), c, w, cv::LINE_AA);
}

}  // namespace semnav
