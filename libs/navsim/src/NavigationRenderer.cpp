/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/core/format.h>
#include <semnav/map/MapRenderer.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/navsim/NavigationRenderer.h>

#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <string>

namespace semnav
{
namespace
{
struct Projector
{
	GridGeometry g;
	int k;
	cv::Point operator()(double x, double y) const
	{
		return MapRenderer::pixel(g, k, x, y);
	}
};

void polyline(
    cv::Mat& img, const Projector& P,
    const std::vector<mrpt::math::TPoint2D>& pts, const cv::Scalar& c, int w)
{
	MapRenderer::polyline(img, P.g, P.k, pts, c, w);
}
}  // namespace

cv::Mat NavigationRenderer::render(
    const SemanticMap& map, const SimulatedNavigation::Result& r, int k)
{
	cv::Mat img = MapRenderer::render(map, k);
	const Projector P{map.geometry(), k};
	const cv::Scalar orange(0, 140, 255), red(0, 0, 230), blue(200, 80, 0),
	    green(0, 170, 0), purple(160, 0, 160), magenta(255, 0, 255);

	for (const auto& p : r.sensedObstacles)
		cv::circle(img, P(p.x, p.y), std::max(1, k / 2), purple, cv::FILLED);
	for (std::size_t i = 0; i + 1 < r.plans.size(); i++)
		polyline(img, P, r.plans[i].path, orange, 1);
	if (!r.plans.empty())
	{
		polyline(img, P, r.plans.back().path, red, 1);
		for (const auto& w : r.plans.back().waypoints)
			cv::circle(img, P(w.x, w.y), k, red, 1, cv::LINE_AA);
	}
	std::vector<mrpt::math::TPoint2D> traj;
	for (const auto& p : r.trajectory) traj.push_back({p.x, p.y});
	polyline(img, P, traj, blue, 2);
	// What the navigator believed (localized runs): thin teal, and the
	// localized start as a teal ring with its heading.
	const cv::Scalar teal(160, 160, 0);
	std::vector<mrpt::math::TPoint2D> est;
	for (const auto& p : r.estimatedTrajectory) est.push_back({p.x, p.y});
	polyline(img, P, est, teal, 1);
	const auto heading = [&](const mrpt::math::TPose2D& p, const cv::Scalar& c)
	{
		const double len = 0.5;
		cv::line(
		    img, P(p.x, p.y),
		    P(p.x + len * std::cos(p.phi), p.y + len * std::sin(p.phi)), c, 2,
		    cv::LINE_AA);
	};
	cv::circle(
	    img, P(r.start.x, r.start.y), 2 * k, green, cv::FILLED, cv::LINE_AA);
	// The true heading when the start was localized (the robot turned on
	// the spot while sweeping), else at the start.
	heading(r.localization ? r.localization->truth : r.start, green);
	if (r.localization)
	{
		const auto& e = r.localization->estimate;
		cv::circle(img, P(e.x, e.y), 3 * k, teal, 2, cv::LINE_AA);
		heading(e, teal);
	}
	cv::circle(
	    img, P(r.finalPose.x, r.finalPose.y), 2 * k, blue, cv::FILLED,
	    cv::LINE_AA);
	if (r.objectId || r.command.kind == NavCommand::Kind::Point)
		cv::circle(
		    img, P(r.objectXY.x, r.objectXY.y), 4 * k, red, 2, cv::LINE_AA);
	// A false arrival: where the robot believed it stood (teal ring) and a
	// red line from where it truly stands to the scene's object (red
	// cross).
	if (r.falseArrival)
	{
		const auto& b = r.believedFinalPose;
		cv::circle(img, P(b.x, b.y), 3 * k, teal, 2, cv::LINE_AA);
		if (r.trueDistance)
		{
			const cv::Point t = P(r.trueObjectXY.x, r.trueObjectXY.y);
			cv::line(img, P(r.finalPose.x, r.finalPose.y), t, red, 2);
			cv::drawMarker(img, t, red, cv::MARKER_TILTED_CROSS, 6 * k, 2);
			cv::putText(
			    img, "FALSE ARRIVAL", P(r.finalPose.x, r.finalPose.y),
			    cv::FONT_HERSHEY_SIMPLEX, 0.5, red, 1, cv::LINE_AA);
		}
	}
	for (const auto& c : r.collisionPoses)
	{
		const cv::Point q = P(c.x, c.y);
		cv::line(
		    img, q - cv::Point(3 * k, 3 * k), q + cv::Point(3 * k, 3 * k),
		    magenta, 2);
		cv::line(
		    img, q - cv::Point(3 * k, -3 * k), q + cv::Point(3 * k, -3 * k),
		    magenta, 2);
	}

	char buf[300];
	std::snprintf(
	    buf, sizeof(buf), "%s: %s, %d replans, %d collisions, %.1f s",
	    r.command.text().c_str(), r.outcome().c_str(), r.replans, r.collisions,
	    r.simTime);
	std::string text = buf;
	if (r.localization)
	{
		std::snprintf(
		    buf, sizeof(buf),
		    "; localized (%s, %d sweeps): start error %.2f m %.1f deg",
		    StopAndScanLocalizer::modeName(r.localization->mode).c_str(),
		    r.localization->sweeps, r.localization->errorXY,
		    r.localization->errorYaw * 180 / M_PI);
		text += buf;
		if (r.localization->drives > 0)
			text += mrpt::format(
			    ", %d drives to look (%.1f m)", r.localization->drives,
			    r.localization->driveLength);
	}
	cv::Mat out(img.rows + 28, img.cols, img.type(), cv::Scalar(255, 255, 255));
	img.copyTo(out(cv::Rect(0, 28, img.cols, img.rows)));
	cv::putText(
	    out, text, {6, 19}, cv::FONT_HERSHEY_SIMPLEX, 0.5, {0, 0, 0}, 1,
	    cv::LINE_AA);
	return out;
}

}  // namespace semnav
