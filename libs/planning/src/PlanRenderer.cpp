/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/map/MapRenderer.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/planning/PlanRenderer.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace semnav
{
namespace
{
cv::Point pixelOf(const GridGeometry& g, const CellIndex& c, int k)
{
	return {c.col * k + k / 2, (g.rows - 1 - c.row) * k + k / 2};
}

void drawPath(
    cv::Mat& img, const GridGeometry& g, const SemanticPlanner::Plan& p, int k)
{
	for (std::size_t i = 1; i < p.path.cells.size(); i++)
		cv::line(
		    img, pixelOf(g, p.path.cells[i - 1], k),
		    pixelOf(g, p.path.cells[i], k), {0, 0, 255}, 2, cv::LINE_AA);
	cv::circle(
	    img, pixelOf(g, p.start, k), 2 * k, {0, 170, 0}, cv::FILLED,
	    cv::LINE_AA);
	if (!p.path.cells.empty())
		cv::circle(
		    img, pixelOf(g, p.path.cells.back(), k), 2 * k, {0, 0, 255},
		    cv::FILLED, cv::LINE_AA);
}

void title(cv::Mat& img, const std::string& t)
{
	cv::putText(
	    img, t, {8, 18}, cv::FONT_HERSHEY_SIMPLEX, 0.5, {0, 0, 0}, 3,
	    cv::LINE_AA);
	cv::putText(
	    img, t, {8, 18}, cv::FONT_HERSHEY_SIMPLEX, 0.5, {255, 255, 255}, 1,
	    cv::LINE_AA);
}
}  // namespace

cv::Mat PlanRenderer::render(
    const SemanticMap& map, const SemanticPlanner::Plan& p, int k)
{
	const GridGeometry& g = p.u.geometry();
	const int w = g.cols * k, h = g.rows * k;

	cv::Mat mapImg = MapRenderer::render(map, k);
	for (int row = 0; row < g.rows; row++)
		for (int col = 0; col < g.cols; col++)
			if (p.goals.isGoal(CellIndex{row, col}))
				cv::rectangle(
				    mapImg, cv::Rect(col * k, (g.rows - 1 - row) * k, k, k),
				    {255, 255, 0}, cv::FILLED);
	drawPath(mapImg, g, p, k);
	title(mapImg, "map, goal cells, path");

	cv::Mat uImg(h, w, CV_8UC3);
	const double L = p.u.L();
	double uMax = 0;
	for (double v : p.u.values())
		if (v < L) uMax = std::max(uMax, v);
	cv::Mat field(g.rows, g.cols, CV_8UC1, cv::Scalar(0));
	double cMax = 0;
	std::vector<double> cost(g.cellCount());
	for (std::size_t i = 0; i < cost.size(); i++)
	{
		cost[i] = p.field.costToGo(g.cellAt(i));
		if (std::isfinite(cost[i])) cMax = std::max(cMax, cost[i]);
	}
	for (int row = 0; row < g.rows; row++)
		for (int col = 0; col < g.cols; col++)
		{
			const std::size_t i = g.index(row, col);
			const double v = p.u.values()[i];
			const cv::Scalar colr =
			    v >= L ? cv::Scalar(0, 0, 0)
			           : cv::Scalar::all(255 - (uMax > 0 ? 200 * v / uMax : 0));
			cv::rectangle(
			    uImg, cv::Rect(col * k, (g.rows - 1 - row) * k, k, k), colr,
			    cv::FILLED);
			if (std::isfinite(cost[i]))
				field.at<uint8_t>(g.rows - 1 - row, col) = static_cast<uint8_t>(
				    1 + 254 * (cMax > 0 ? cost[i] / cMax : 0));
		}
	drawPath(uImg, g, p, k);
	title(uImg, "traversability u");

	cv::Mat fieldBig, fieldImg;
	cv::resize(field, fieldBig, {w, h}, 0, 0, cv::INTER_NEAREST);
	cv::applyColorMap(fieldBig, fieldImg, cv::COLORMAP_JET);
	fieldImg.setTo(cv::Scalar(0, 0, 0), fieldBig == 0);
	drawPath(fieldImg, g, p, k);
	title(fieldImg, "diffusion field (cost to go)");

	cv::Mat out(
	    std::max(mapImg.rows, h), mapImg.cols + 2 * w + 20, CV_8UC3,
	    cv::Scalar(255, 255, 255));
	mapImg.copyTo(out(cv::Rect(0, 0, mapImg.cols, mapImg.rows)));
	uImg.copyTo(out(cv::Rect(mapImg.cols + 10, 0, w, h)));
	fieldImg.copyTo(out(cv::Rect(mapImg.cols + w + 20, 0, w, h)));
	return out;
}

}  // namespace semnav
