/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <array>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

namespace semnav
{
/** A 3D shape descriptor of a detected object, from its points and normals
 * in one sweep: size and position, the height profile, the widths of its
 * lower, middle and upper thirds, how its surfaces face (up, sideways, how
 * the side normals turn across it: a cylinder's do, a box face's do not),
 * the curvature of its front, the spread of its points, the heights its
 * up-facing surfaces lie at (one for a table, one per step for stairs) and its
 * surroundings (walls beside it, how much of its box it fills), and three
 * coarse grids of its points in its own frame (height against depth along
 * the line of sight and against the side, the extents split in
 * kGridSide): where the points lie and how up-facing they are there (a
 * flight of stairs climbs, a basin's top overhangs its pedestal), and the
 * steps along its sweep columns. Used by
 * ShapeVerifier to tell washbasins from tables, wastebaskets from chairs
 * and boxes, and stairs from furniture where the window detector cannot. */
class ObjectShape
{
public:
	/** The scalar features (size, profile, surfaces, surroundings). */
	static constexpr int kBaseFeatures = 31;
	/** Cells per side of each object-frame grid. */
	static constexpr int kGridSide = 8;
	/** The grids, after the scalar features: the share of the points in
	 * each height x depth cell, their mean |normal z| there (-1: none) and
	 * the share in each height x side cell; rows from the ground up. */
	static constexpr int kGridFeatures = 3 * kGridSide * kGridSide;
	/** After the grids: steps along the sweep's columns (a flight's
	 * risers, each a run farther and a rise higher than the one below):
	 * steps per column, the share of columns with two, the median run and
	 * rise (m). */
	static constexpr int kStepFeatures = 4;
	static constexpr int kStepsAt = kBaseFeatures + kGridFeatures;
	static constexpr int kFeatures = kStepsAt + kStepFeatures;
	using Features = std::array<float, kFeatures>;

	/** The descriptor's columns a forest over `count` features reads,
	 * in order: the scalar features, then the grids and / or the steps
	 * (kBaseFeatures, + kGridFeatures, + kStepFeatures, or all); empty
	 * for any other count. */
	static std::vector<int> columnsOf(int count);
	/** The feature count of the scalar features with the grids and / or
	 * the steps. */
	static constexpr int featureCount(bool grids, bool steps)
	{
		return kBaseFeatures + (grids ? kGridFeatures : 0) +
		       (steps ? kStepFeatures : 0);
	}

	/** Short names of the features, in order. */
	static const std::array<std::string, kFeatures>& names();

	/** Index of the one feature describe() leaves 0: how many of its
	 * class's cascade windows cover the candidate (CascadeDetector fills
	 * it; the forest weighs the window detector's evidence with the
	 * shape). */
	static constexpr int kCascadeSupport = 30;

	/** The descriptor of the object whose sweep pixels are `object`.
	 * `points`, `normals` CV_32FC3 (robot frame, NaN / zero where none),
	 * `normalMask` CV_8U, `labels` CV_8U rule labels (may be empty),
	 * `surroundings` the sweep pixels of the box the object was measured in
	 * (a superset of `object`), `groundZ` the ground height. All zero when
	 * `object` has no valid point. `steps` false leaves the steps 0 (a
	 * forest that does not read them). */
	static Features describe(
	    const cv::Mat& points, const cv::Mat& normals,
	    const cv::Mat& normalMask, const cv::Mat& labels,
	    const std::vector<cv::Point>& object,
	    const std::vector<cv::Point>& surroundings, double groundZ,
	    bool steps = true);
};

}  // namespace semnav
