/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/map/MapRenderer.h>

#include <opencv2/imgproc.hpp>

namespace semnav
{
cv::Scalar MapRenderer::labelColor(Label l)
{
	switch (l)
	{
		case Label::Door:
			return {0, 140, 255};  // orange
		case Label::Stairs:
			return {200, 0, 200};  // magenta
		case Label::Washbasin:
			return {255, 128, 0};  // blue
		case Label::Wastebasket:
			return {0, 180, 0};  // green
		case Label::Sidewalk:
			return {190, 190, 190};
		case Label::Grass:
			return {120, 220, 120};
		case Label::Ceiling:
			return {200, 230, 255};
		case Label::Wall:
		case Label::Obstacle:
			return {0, 0, 0};
		default:
			return {255, 255, 255};
	}
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
			if (ls.contains(Label::Grass)) col = labelColor(Label::Grass);
			if (ls.contains(Label::Sidewalk)) col = labelColor(Label::Sidewalk);
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
	const std::pair<const char*, cv::Scalar> items[] = {
	    {"free floor", {255, 255, 255}},
	    {"unknown", {225, 225, 225}},
	    {"wall / obstacle", {0, 0, 0}},
	    {"door", labelColor(Label::Door)},
	    {"stairs", labelColor(Label::Stairs)},
	    {"washbasin", labelColor(Label::Washbasin)},
	    {"wastebasket", labelColor(Label::Wastebasket)},
	    {"sidewalk", labelColor(Label::Sidewalk)},
	    {"grass", labelColor(Label::Grass)}};
	for (const auto& [name, col] : items)
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

}  // namespace semnav
