/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/ClassRegistry.h>
#include <semnav/common/Error.h>
#include <semnav/common/Label.h>
#include <semnav/common/Percentile.h>
#include <semnav/detection/ObjectProposals.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace semnav
{
cv::Mat ObjectProposals::objectMask(
    const cv::Mat& points, const cv::Mat& labels, const cv::Mat& areaIds,
    double groundZ, const Params& params)
{
	if (points.type() != CV_32FC3)
		throw Error("ObjectProposals: points must be CV_32FC3");
	if (!labels.empty() &&
	    (labels.type() != CV_8UC1 || labels.size() != points.size()))
		throw Error(
		    "ObjectProposals: labels must be CV_8U of the points' size");
	const float zMin = static_cast<float>(groundZ + params.floorTolerance);
	const float zMax = static_cast<float>(groundZ + params.maxHeight);
	// Surfaces (wall, door, ceiling areas) are not objects, except a
	// "wall" that stays low: the rules call the broad side of a near object
	// a wall, but real walls reach far higher than maxHeight.
	cv::Mat surface(points.size(), CV_8U, cv::Scalar(0));
	const LabelSet structure = ClassRegistry::instance().select(
	    [](const ClassInfo& c) { return c.structure; });
	if (!labels.empty())
		for (int r = 0; r < points.rows; r++)
		{
			const auto* l = labels.ptr<uint8_t>(r);
			auto* s = surface.ptr<uint8_t>(r);
			for (int c = 0; c < points.cols; c++)
			{
				s[c] = structure.contains(static_cast<Label>(l[c]));
			}
		}
	// Surfaces: the segmentation's areas if given, else 8-connected
	// pixels of a surface label.
	cv::Mat surfaceIds;
	int nSurfaces = 0;
	if (!areaIds.empty())
	{
		if (areaIds.type() != CV_32SC1 || areaIds.size() != points.size())
			throw Error(
			    "ObjectProposals: area ids must be CV_32S of the points' "
			    "size");
		surfaceIds = cv::Mat(points.size(), CV_32S, cv::Scalar(0));
		areaIds.copyTo(surfaceIds, surface);
		double mx = 0;
		cv::minMaxLoc(surfaceIds, nullptr, &mx);
		nSurfaces = static_cast<int>(mx) + 1;
	}
	else
		nSurfaces = cv::connectedComponents(surface, surfaceIds, 8, CV_32S);
	std::vector<float> surfaceTop(static_cast<std::size_t>(nSurfaces), -1e9f);
	for (int r = 0; r < points.rows; r++)
	{
		const auto* p = points.ptr<cv::Vec3f>(r);
		const auto* id = surfaceIds.ptr<int>(r);
		for (int c = 0; c < points.cols; c++)
			if (id[c] > 0 && std::isfinite(p[c][2]))
			{
				float& t = surfaceTop[static_cast<std::size_t>(id[c])];
				t = std::max(t, p[c][2]);
			}
	}
	cv::Mat mask(points.size(), CV_8U, cv::Scalar(0));
	for (int r = 0; r < points.rows; r++)
	{
		const auto* p = points.ptr<cv::Vec3f>(r);
		const auto* id = surfaceIds.ptr<int>(r);
		auto* m = mask.ptr<uint8_t>(r);
		for (int c = 0; c < points.cols; c++)
		{
			// NaN fails both comparisons.
			if (!(p[c][2] >= zMin && p[c][2] <= zMax)) continue;
			if (surface.at<uint8_t>(r, c) &&
			    (id[c] <= 0 ||
			     surfaceTop[static_cast<std::size_t>(id[c])] > zMax))
				continue;
			m[c] = 1;
		}
	}
	return mask;
}

std::vector<std::vector<ObjectProposal>> ObjectProposals::find(
    const cv::Mat& points, const cv::Mat& labels, const cv::Mat& areaIds,
    double groundZ, const PanoramicProjection* projection,
    const std::vector<double>& topLimits, const Params& params)
{
	return findInMask(
	    points, objectMask(points, labels, areaIds, groundZ, params), groundZ,
	    projection, topLimits, params);
}

std::vector<std::vector<ObjectProposal>> ObjectProposals::findInMask(
    const cv::Mat& points, const cv::Mat& sweepMask, double groundZ,
    const PanoramicProjection* projection, const std::vector<double>& topLimits,
    const Params& params)
{
	if (sweepMask.type() != CV_8UC1 || sweepMask.size() != points.size())
		throw Error(
		    "ObjectProposals: the object mask must be CV_8U of the points' "
		    "size");
	// Horizontal range and height above the ground of the object points
	// (range 0 elsewhere).
	cv::Mat range(points.size(), CV_32F, cv::Scalar(0));
	cv::Mat height(points.size(), CV_32F, cv::Scalar(0));
	for (int r = 0; r < points.rows; r++)
	{
		const auto* p = points.ptr<cv::Vec3f>(r);
		const auto* m = sweepMask.ptr<uint8_t>(r);
		auto* d = range.ptr<float>(r);
		auto* h = height.ptr<float>(r);
		for (int c = 0; c < points.cols; c++)
			if (m[c])
			{
				d[c] = std::hypot(p[c][0], p[c][1]);
				h[c] = p[c][2] - static_cast<float>(groundZ);
			}
	}
	if (projection && !projection->empty())
	{
		range = projection->toPanoramic(range, cv::INTER_NEAREST);
		height = projection->toPanoramic(height, cv::INTER_NEAREST);
	}
	std::vector<std::vector<ObjectProposal>> out;
	// A negative limit keeps no point (nothing to search).
	for (double limit : topLimits)
		out.push_back(
		    limit < 0
		        ? std::vector<ObjectProposal>()
		        : regions(range, height, static_cast<float>(limit), params));
	return out;
}

std::vector<ObjectProposal> ObjectProposals::regions(
    const cv::Mat& range, const cv::Mat& height, float topLimit,
    const Params& params)
{
	// Regions: object pixels (range > 0) at most topLimit high, within
	// joinRadius of each other, whose ranges are continuous (a flood fill;
	// the object pixels are a small part of the image).
	cv::Mat ids(range.size(), CV_32S, cv::Scalar(0));
	const auto isObject = [&](int y, int x)
	{ return range.at<float>(y, x) > 0 && height.at<float>(y, x) <= topLimit; };
	std::vector<cv::Point> stack;
	std::vector<float> ranges, heights;
	std::vector<ObjectProposal> out;
	const int rad = params.joinRadius;
	int n = 0;
	for (int r0 = 0; r0 < range.rows; r0++)
		for (int c0 = 0; c0 < range.cols; c0++)
		{
			if (ids.at<int>(r0, c0) || !isObject(r0, c0)) continue;
			const int id = ++n;
			ranges.clear();
			heights.clear();
			int x0 = c0, x1 = c0, y0 = r0, y1 = r0, taller = 0;
			ids.at<int>(r0, c0) = id;
			stack.assign(1, cv::Point(c0, r0));
			while (!stack.empty())
			{
				const cv::Point a = stack.back();
				stack.pop_back();
				const float ra = range.at<float>(a);
				ranges.push_back(ra);
				heights.push_back(height.at<float>(a));
				x0 = std::min(x0, a.x);
				x1 = std::max(x1, a.x);
				y0 = std::min(y0, a.y);
				y1 = std::max(y1, a.y);
				const float gap = static_cast<float>(params.gapAt(ra));
				for (int y = std::max(0, a.y - rad);
				     y <= std::min(range.rows - 1, a.y + rad); y++)
				{
					const auto* d = range.ptr<float>(y);
					const auto* h = height.ptr<float>(y);
					auto* o = ids.ptr<int>(y);
					for (int x = std::max(0, a.x - rad);
					     x <= std::min(range.cols - 1, a.x + rad); x++)
					{
						if (!(d[x] > 0) || std::abs(d[x] - ra) > gap) continue;
						if (h[x] > topLimit)
						{
							// Marked -id: counted once per region.
							if (o[x] != -id)
							{
								o[x] = -id;
								taller++;
							}
							continue;
						}
						if (o[x]) continue;
						o[x] = id;
						stack.emplace_back(x, y);
					}
				}
			}
			if (static_cast<int>(ranges.size()) < params.minPixels) continue;
			ObjectProposal p;
			p.box = cv::Rect(x0, y0, x1 - x0 + 1, y1 - y0 + 1);
			p.pixels = static_cast<int>(ranges.size());
			p.nearRange = percentile(ranges, 0.1);
			p.farRange = percentile(ranges, 0.9);
			p.bottom = percentile(heights, 0.05);
			p.top = percentile(heights, 0.95);
			p.tallerPixels = taller;
			out.push_back(p);
		}
	return out;
}

}  // namespace semnav
