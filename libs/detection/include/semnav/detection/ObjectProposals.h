/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/detection/PanoramicProjection.h>

#include <opencv2/core/mat.hpp>
#include <vector>

namespace semnav
{
/** One region of a detection image where an object may stand: a connected
 * group of points that the rule classifier left to the objects (not floor,
 * wall, ceiling or door, above the ground). */
struct ObjectProposal
{
	/** Bounding box in detection-image pixels (panoramic or sweep). */
	cv::Rect box;
	/** Detection-image pixels of the region. */
	int pixels = 0;
	/** Horizontal range of its points (m): 10th and 90th percentile. */
	double nearRange = 0, farRange = 0;
	/** Height of its lowest points above the ground (m, 5th percentile):
	 * near 0 when its foot is seen, so that an object in it is seen
	 * whole (within about 1.7 m the lowest tilt line no longer reaches
	 * the floor and objects are cut). */
	double bottom = 0;
	/** Height of its top above the ground (m, 95th percentile). */
	double top = 0;
	/** Object pixels higher than the height limit that join it (range
	 * within the gap, within the join radius): the region is the lower
	 * part of something taller (a pillar, a cabinet, a washbasin's
	 * pedestal). */
	int tallerPixels = 0;
};

/** Region proposals for the cascades: the rule classifier labels floor,
 * walls, ceiling and doors, and leaves objects standing on the floor as
 * `obstacle` (or unknown) points; only windows around those need a cascade
 * search, and each region's range bounds the pixel size an object of a
 * given real size can have there. */
class ObjectProposals
{
public:
	struct Params
	{
		/** Points this close to the ground are floor (m). */
		double floorTolerance = 0.04;
		/** Points higher than this above the ground are not part of an
		 * object standing on it (m). */
		double maxHeight = 2.0;
		/** Regions with fewer detection-image pixels are dropped. */
		int minPixels = 10;
		/** Object pixels at most this far apart in the image (pixels,
		 * Chebyshev distance) belong to one region when their ranges are
		 * close (rangeGap). */
		int joinRadius = 1;
		/** Neighbouring pixels whose horizontal ranges differ by more than
		 * rangeGap + rangeGapPerM x range (m) are in different regions: an
		 * object in front of another is its own region, with its own
		 * range. */
		double rangeGap = 0.2, rangeGapPerM = 0.05;
		/** rangeGap + rangeGapPerM x `range` (m). */
		double gapAt(double range) const
		{
			return rangeGap + rangeGapPerM * range;
		}
	};

	/** CV_8U 0/1, sweep layout: points (CV_32FC3, robot frame, NaN where
	 * invalid) above groundZ + floorTolerance and at most maxHeight above
	 * the ground, not in an area labelled ceiling, wall or door in
	 * `labels` (CV_8U, may be empty) that reaches higher than maxHeight.
	 * The areas are those of `areaIds` (CV_32S segmentation areas, 0 =
	 * none) if not empty, else 8-connected pixels of a surface label
	 * (the rules may call the broad side of a near object a wall; real
	 * walls reach the ceiling). Ground labels are left to the height test
	 * (a low object's top can be swallowed by a floor area). */
	static cv::Mat objectMask(
	    const cv::Mat& points, const cv::Mat& labels, const cv::Mat& areaIds,
	    double groundZ, const Params& params);

	/** The proposals of a sweep, in detection-image pixels (the panoramic
	 * image of `projection` when it is not null and not empty, else the
	 * sweep layout), once per height limit in `topLimits`: the regions of
	 * the object points at most that high above the ground. An object of a
	 * class whose top is below the limit lies within one; with the limit,
	 * a table top or a cabinet's upper part no longer joins the objects
	 * beside it into one large region. */
	static std::vector<std::vector<ObjectProposal>> find(
	    const cv::Mat& points, const cv::Mat& labels, const cv::Mat& areaIds,
	    double groundZ, const PanoramicProjection* projection,
	    const std::vector<double>& topLimits, const Params& params);

	/** find() over an objectMask() computed before (CV_8U 0/1, sweep
	 * layout): the same proposals. */
	static std::vector<std::vector<ObjectProposal>> findInMask(
	    const cv::Mat& points, const cv::Mat& mask, double groundZ,
	    const PanoramicProjection* projection,
	    const std::vector<double>& topLimits, const Params& params);

	/** The regions of one height limit: `range` (CV_32F, horizontal range,
	 * 0 where no object point) and `height` (CV_32F, above the ground) in
	 * detection-image layout. */
	static std::vector<ObjectProposal> regions(
	    const cv::Mat& range, const cv::Mat& height, float topLimit,
	    const Params& params);
};

}  // namespace semnav
