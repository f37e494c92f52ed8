/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/common/Label.h>
#include <semnav/detection/CascadeDetector.h>

#include <cstddef>
#include <functional>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

namespace semnav
{
/** Samples for one class's ShapeVerifier (what semnav-train-shape runs):
 * perception and the cascade detector on simulated datasets, every
 * candidate of the class that passes the 3D size check described
 * (ObjectShape) and labelled by the ground truth. */
class ShapeTraining
{
public:
	struct Samples
	{
		/** CV_32F, one ObjectShape::Features per row (the columns
		 * ObjectShape::columnsOf gives without grids or steps); CV_32S
		 * 1 / 0. */
		cv::Mat features, isObject;
		/** The object and other samples kept (after the subsets). */
		std::size_t objects = 0, others = 0;
		/** Candidates neither clearly an object nor clearly not (left out). */
		std::size_t ambiguous = 0;
		/** Of them, boxes on an object whose measured points are mostly
		 * something else (Params::minPurity). */
		std::size_t impure = 0;
		std::size_t sweeps = 0;
	};

	/** An object: the measured box has IoU >= objectIou with an object of
	 * the class in the ground truth; not an object: IoU < otherIou with
	 * every one; else ambiguous. */
	struct Params
	{
		double objectIou = 0.3, otherIou = 0.1;
		/** Overrides the class's min_neighbors (-1: keep): looser than
		 * detection, so that the forest sees what the cascade confuses. */
		int minNeighbors = 0;
		/** Overrides the class's max_stages (-1: keep). */
		int maxStages = -1;
		/** At most this many object samples per other sample (a seeded
		 * random subset; 0: all). */
		double maxObjectsPerOther = 0;
		/** At most this many samples in all (a seeded random subset of
		 * each kind, in proportion; 0: all). */
		std::size_t maxSamples = 0;
		uint64_t seed = 1;
		/** With ObjectShape's object-frame grids, and with its steps
		 * along the sweep's columns. */
		bool grids = true;
		bool steps = false;
		/** An object sample's measured pixels are at least this share of
		 * that object's (ground truth); fewer: ambiguous (0: no check). */
		double minPurity = 0;
	};

	/** Throws Error / IoError on unreadable datasets. `progress(done, all)`
	 * is called after each sweep of each dataset. */
	static Samples collect(
	    const std::vector<std::string>& datasets,
	    CascadeDetector::TOptions detector, Label label, const Params& params,
	    const std::function<void(const std::string&, std::size_t, std::size_t)>&
	        progress = {});
};

}  // namespace semnav
