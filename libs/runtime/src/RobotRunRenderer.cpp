/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/core/format.h>
#include <semnav/common/AtomicFile.h>
#include <semnav/common/Error.h>
#include <semnav/map/MapRenderer.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/runtime/RobotRunRenderer.h>
#include <semnav/runtime/RobotSession.h>

#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace semnav
{
cv::Mat RobotRunRenderer::render(
    const SemanticMap& map, const RobotSession& session, int k)
{
	cv::Mat img = MapRenderer::render(map, k);
	const GridGeometry& g = map.geometry();
	const cv::Scalar orange(0, 140, 255), red(0, 0, 230), blue(200, 80, 0);
	const auto& plans = session.plans();
	for (std::size_t i = 0; i + 1 < plans.size(); i++)
		MapRenderer::polyline(img, g, k, plans[i].path, orange, 1);
	if (!plans.empty())
		MapRenderer::polyline(img, g, k, plans.back().path, red, 1);
	std::vector<mrpt::math::TPoint2D> traj;
	for (const auto& p : session.trajectory()) traj.push_back({p.x, p.y});
	MapRenderer::polyline(img, g, k, traj, blue, 2);
	if (!session.trajectory().empty())
	{
		const auto& p = session.trajectory().back();
		cv::circle(
		    img, MapRenderer::pixel(g, k, p.x, p.y), 2 * k, blue, cv::FILLED,
		    cv::LINE_AA);
		cv::line(
		    img, MapRenderer::pixel(g, k, p.x, p.y),
		    MapRenderer::pixel(
		        g, k, p.x + 0.5 * std::cos(p.phi), p.y + 0.5 * std::sin(p.phi)),
		    blue, 2, cv::LINE_AA);
	}
	const std::string text = mrpt::format(
	    "semnav-robot: %d commands, %d sweeps inserted, %zu objects, %zu "
	    "plans",
	    session.commandsDone(), session.sweepsInserted(),
	    map.instances().size(), plans.size());
	cv::Mat out(img.rows + 28, img.cols, img.type(), cv::Scalar(255, 255, 255));
	img.copyTo(out(cv::Rect(0, 28, img.cols, img.rows)));
	cv::putText(
	    out, text, {6, 19}, cv::FONT_HERSHEY_SIMPLEX, 0.5, {0, 0, 0}, 1,
	    cv::LINE_AA);
	return out;
}

void RobotRunRenderer::write(
    const SemanticMap& map, const RobotSession& session,
    const std::string& path)
{
	std::vector<uchar> png;
	if (!cv::imencode(".png", render(map, session), png))
		throw IoError("cannot encode " + path);
	writeFileAtomically(path, std::string(png.begin(), png.end()));
}

}  // namespace semnav
