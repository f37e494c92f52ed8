/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/math/TBoundingBox.h>
#include <mrpt/math/TPoint3D.h>
#include <semnav/common/Label.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace semnav
{
/** One object of the semantic map (a washbasin, a door...), merged from the
 * detections of several sweeps. World frame, metres. */
struct ObjectInstance
{
	/** 1-based id, also the value of the map's "objects" layer. */
	int id = 0;
	Label label = Label::Unknown;
	/** Robust mean of the detections' centroids (see addSighting()). */
	mrpt::math::TPoint3D centroid{0, 0, 0};
	/** The detections' centroids, one per sweep that detected it (in
	 * memory only: a loaded map starts again from its centroid). */
	std::vector<mrpt::math::TPoint3D> sightings;
	/** Size of each sighting's detection: x = its width across the line
	 * of sight (the larger horizontal side), z = its height (in memory
	 * only, like `sightings`). */
	std::vector<mrpt::math::TPoint3D> sightingSizes;
	/** Axis-aligned bounds of all detections. */
	mrpt::math::TPoint3D minCorner{0, 0, 0}, maxCorner{0, 0, 0};
	/** Sweeps in which the object was detected. */
	std::size_t observations = 0;
	/** Sweeps that had it in view (line of sight to its centroid within
	 * the sweep's field of view and range; doors: seen nearly straight on
	 * and mostly unhidden, SemanticMap::TOptions::doorMinDetectionRatio),
	 * detected or not. */
	std::size_t views = 0;
	/** Sum of the horizontal unit normals of its regions (doors; world
	 * frame, each turned to agree with the sum so far: a door seen from
	 * both sides), (0,0,0) when unknown (in memory only). */
	mrpt::math::TPoint3D normalSum{0, 0, 0};
	/** Doors: 2 for a double door joined from two instances, one per leaf
	 * (SemanticMap::TOptions::doubleDoorMaxWidth); its centroid is then the
	 * middle between its leaves' sightings (in memory only). */
	int leaves = 1;
	/** The best shape check score of its detections (Detection::shapeScore;
	 * 1 for classes without a shape model). Doors: the largest share of a
	 * whole leaf seen nearly straight on (SemanticMap::doorLeafScore()). */
	double bestShapeScore = 1;

	/** Adds one sweep's detection centroid and recomputes `centroid` as
	 * the mean of the sightings within `inlierRadius` (horizontally) of
	 * their per-axis median: a detection box that swallowed a neighbour,
	 * or a false alarm merged by footprint overlap, no longer drags the
	 * object away. */
	void addSighting(
	    const mrpt::math::TPoint3D& c, double inlierRadius,
	    double maxWeightWidth = 0)
	{
		if (sightings.empty() && observations > 0)
			sightings.push_back(centroid);
		sightings.push_back(c);
		recentre(inlierRadius, maxWeightWidth);
	}

	/** Replaces the last sighting (and its size, if recorded) by a better
	 * one of the same sweep, and recomputes `centroid` as addSighting()
	 * does. No-op without sightings. */
	void replaceLastSighting(
	    const mrpt::math::TPoint3D& c, const mrpt::math::TPoint3D& size,
	    double inlierRadius, double maxWeightWidth = 0)
	{
		if (sightings.empty()) return;
		sightings.back() = c;
		if (!sightingSizes.empty()) sightingSizes.back() = size;
		recentre(inlierRadius, maxWeightWidth);
	}

	/** Sets `centroid` to the mean of the sightings within `inlierRadius`
	 * (horizontally) of their per-axis median (all of them when none is;
	 * unchanged without sightings). `maxWeightWidth` > 0: each weighted by
	 * the square of its detection's width (sightingSizes x), widths above
	 * `maxWeightWidth` counting as that: a cut view of a door or a piece of
	 * jamb beside it pulls it less than a whole view, and a region that
	 * swallowed wall no more than one a door wide (doors,
	 * SemanticMap::TOptions::doorCentroidMaxWeightWidth); unweighted when a
	 * sighting has no size. */
	void recentre(double inlierRadius, double maxWeightWidth = 0)
	{
		if (sightings.empty()) return;
		const std::vector<bool> in = inlierMask(inlierRadius);
		const bool any = std::find(in.begin(), in.end(), true) != in.end();
		const bool weighted =
		    maxWeightWidth > 0 && sightingSizes.size() == sightings.size();
		mrpt::math::TPoint3D sum(0, 0, 0);
		double total = 0;
		for (std::size_t i = 0; i < sightings.size(); i++)
		{
			if (any && !in[i]) continue;
			// A width of 0 (unknown) weighs as a 1 cm sliver.
			const double w = weighted ? std::min(
			                                std::max(sightingSizes[i].x, 0.01),
			                                std::max(maxWeightWidth, 0.01))
			                          : 1.0;
			sum = sum + sightings[i] * (w * w);
			total += w * w;
		}
		centroid = sum * (1.0 / total);
	}

	/** The sightings within `inlierRadius` (horizontally) of their per-axis
	 * median (none without sightings). */
	std::vector<mrpt::math::TPoint3D> inlierSightings(double inlierRadius) const
	{
		std::vector<mrpt::math::TPoint3D> in;
		const std::vector<bool> mask = inlierMask(inlierRadius);
		for (std::size_t i = 0; i < sightings.size(); i++)
			if (mask[i]) in.push_back(sightings[i]);
		return in;
	}

	/** Per sighting: whether it lies within `inlierRadius` (horizontally)
	 * of the sightings' per-axis median. */
	std::vector<bool> inlierMask(double inlierRadius) const
	{
		std::vector<bool> in(sightings.size(), false);
		if (sightings.empty()) return in;
		const double mx = median(sightings, &mrpt::math::TPoint3D::x),
		             my = median(sightings, &mrpt::math::TPoint3D::y);
		for (std::size_t i = 0; i < sightings.size(); i++)
			in[i] = std::hypot(sightings[i].x - mx, sightings[i].y - my) <=
			        inlierRadius;
		return in;
	}

	/** Typical size of one detection of it (per-axis median of
	 * `sightingSizes`): unlike extent(), not inflated by the spread of the
	 * sightings or one box that swallowed a neighbour. extent() when no
	 * size was recorded (a loaded map, addInstance()). */
	mrpt::math::TPoint3D typicalSize() const
	{
		if (sightingSizes.empty())
		{
			const auto e = extent();
			return {std::max(e.x, e.y), 0, e.z};
		}
		return {
		    median(sightingSizes, &mrpt::math::TPoint3D::x), 0,
		    median(sightingSizes, &mrpt::math::TPoint3D::z)};
	}

	/** Its box (minCorner, maxCorner). */
	mrpt::math::TBoundingBox box() const
	{
		return {
		    minCorner, maxCorner,
		    mrpt::math::TBoundingBox::CTOR_FLAGS::AllowUnordered};
	}

	/** Whether its footprint (x, y) and `b`'s overlap, borders included. */
	bool footprintOverlaps(const mrpt::math::TBoundingBox& b) const
	{
		return minCorner.x <= b.max.x && b.min.x <= maxCorner.x &&
		       minCorner.y <= b.max.y && b.min.y <= maxCorner.y;
	}

	/** Grows its box to take in `b`. */
	void takeInBox(const mrpt::math::TBoundingBox& b)
	{
		minCorner = {
		    std::min(minCorner.x, b.min.x), std::min(minCorner.y, b.min.y),
		    std::min(minCorner.z, b.min.z)};
		maxCorner = {
		    std::max(maxCorner.x, b.max.x), std::max(maxCorner.y, b.max.y),
		    std::max(maxCorner.z, b.max.z)};
	}

	mrpt::math::TPoint3D extent() const
	{
		return {
		    maxCorner.x - minCorner.x, maxCorner.y - minCorner.y,
		    maxCorner.z - minCorner.z};
	}

	/** The median of one axis of non-empty `points`. */
	static double median(
	    const std::vector<mrpt::math::TPoint3D>& points,
	    double mrpt::math::TPoint3D::*axis)
	{
		std::vector<double> v;
		for (const auto& p : points) v.push_back(p.*axis);
		std::sort(v.begin(), v.end());
		const std::size_t h = v.size() / 2;
		return v.size() % 2 ? v[h] : 0.5 * (v[h - 1] + v[h]);
	}
};

}  // namespace semnav
