/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <semnav/cascade/RangeGate.h>
#include <semnav/common/Label.h>
#include <semnav/detection/DetectionImage.h>
#include <semnav/detection/DetectionPass.h>
#include <semnav/detection/ObjectProposals.h>
#include <semnav/detection/ObjectShape.h>
#include <semnav/detection/PanoramicProjection.h>
#include <semnav/perception/Detection.h>
#include <semnav/perception/LabeledSweep.h>
#include <semnav/scan/Sweep.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <opencv2/core/mat.hpp>
#include <optional>
#include <string>
#include <vector>

namespace semnav
{
/** Finds washbasins, wastebaskets and stairs in a sweep with one trained
 * Haar cascade per class (paper sec. 2.2.2), run by OpenCV's
 * cv::CascadeClassifier::detectMultiScale on the sweep's detection image
 * (DetectionImage of its normals) scaled by the class's `upscale` (a
 * wastebasket 3 m away is about 11 x 14 pixels, below the 20 x 20 window).
 * By default the detection image is resampled to azimuth x elevation
 * (PanoramicProjection) so that objects beside the robot keep their shape.
 * Every detection is then measured in 3D from the range data inside its box
 * and rejected when its size is implausible for the class (the paper:
 * "having direct geometrical information about a detected object we can
 * often reject false classifications just by analysing its real size"). */
class CascadeDetector
{
public:
	/** One class, INI section [CascadeDetector.<label>]. */
	struct TClassOptions : public mrpt::config::CLoadableOptions
	{
		TClassOptions();
		explicit TClassOptions(Label l);
		void loadFromConfigFile(
		    const mrpt::config::CConfigFileBase& c,
		    const std::string& section) override;
		void saveToConfigFile(
		    mrpt::config::CConfigFileBase& c,
		    const std::string& section) const override;
		static const std::vector<std::string>& knownKeys();

		Label label = Label::Unknown;
		/** cascade: the cascade XML; a relative path is relative to the
		 * INI file's directory. */
		std::string cascade;
		/** upscale: the detection image (rows between min_elevation_deg
		 * and max_elevation_deg) is scaled by this before the cascade runs
		 * (the "near" pass). */
		double upscale = 1.0;
		double minElevation = -M_PI / 2, maxElevation = M_PI / 2;
		/** far_upscale (0 = no far pass), far_below_px: objects smaller
		 * than far_below_px (box side, detection-image pixels) are searched
		 * in the rows between far_min_elevation_deg and
		 * far_max_elevation_deg scaled by far_upscale (small objects are
		 * far, hence near the horizon). */
		double farUpscale = 0, farBelowPx = 0;
		double farMinElevation = -0.2, farMaxElevation = 0.2;
		/** scale_factor, min_neighbors: detectMultiScale's. */
		double scaleFactor = 1.1;
		int minNeighbors = 3;
		/** window_step: with range_scales, the step between windows at
		 * every pyramid level (level pixels); 0: detectMultiScale's (2 up
		 * to scale 2, 1 above). */
		int windowStep = 0;
		/** max_size_px: largest box side searched (detection-image
		 * pixels; 0: the image). */
		double maxSizePx = 0;

		/** The passes for a detection image whose rows span elevations
		 * [el0, el1] (rad) evenly, for a cascade window of `window`. */
		std::vector<DetectionPass> passes(
		    int rows, double el0, double el1, cv::Size window) const;
		/** min_width_m, max_width_m: extent across the line of sight of
		 * the object's points. */
		double minWidth = 0.0, maxWidth = 100.0;
		/** min_top_m, max_top_m: height of the object's top (95th
		 * percentile of z) above the ground. */
		double minTop = 0.0, maxTop = 100.0;
		/** max_depth_m: object points lie at most this far (horizontally)
		 * behind its nearest part in the box's centre. */
		double maxDepth = 1.0;
		/** min_size_m, max_size_m: the larger side (width or height) of a
		 * whole object of the class; min_cut_size_m: of an object whose
		 * foot is not seen (cut by the lowest tilt line). With proposals,
		 * they bound the window sides searched at a proposal's range. */
		double minSize = 0.2, maxSize = 2.0, minCutSize = 0.2;
		/** proposal_min_neighbors: detectMultiScale's min_neighbors in the
		 * windows around proposals (-1: min_neighbors): a region the rules
		 * left to objects, of the right real size, needs less agreement
		 * between neighbouring windows than anywhere in the image. */
		int proposalMinNeighbors = -1;
		/** border_px: the whole-image search pads each pass's band with
		 * this many zero pixels (detection-image pixels, scaled with the
		 * pass) on the left, the right and below the lowest elevation, as
		 * the training samples of objects at the image's edge are padded:
		 * windows around objects cut by the edge then exist. 0: none. */
		double borderPx = 0;
		/** min_points: fewer object points than this: rejected. */
		int minPoints = 15;
		/** channel: this class's detection image (DetectionImage); unset:
		 * the [CascadeDetector] channel. */
		std::optional<DetectionChannel> channel;
		/** shape_model: a ShapeVerifier forest (relative paths as
		 * `cascade`); empty: no shape check. min_shape_score: detections
		 * that pass the size check but whose ObjectShape the forest scores
		 * lower are rejected ("shape"). */
		std::string shapeModel;
		double minShapeScore = 0.5;
		/** side_bearing_deg, side_min_shape_score: a detection whose
		 * centroid lies at a bearing of side_bearing_deg or more (stored
		 * in rad) is beside the robot, where the tilt axis points at it and
		 * a sweep sees it as a thin slice: there the forest must also score
		 * it side_min_shape_score (minShapeScoreAt()). side_bearing_deg 90
		 * or side_min_shape_score 0 (at most min_shape_score): no stricter
		 * check. */
		double sideBearing = M_PI / 2;
		double sideMinShapeScore = 0;
		/** The shape score a detection whose centroid lies at `bearing`
		 * (rad, either side) needs. */
		double minShapeScoreAt(double bearing) const
		{
			return std::abs(bearing) >= sideBearing && sideBearing < M_PI / 2
			           ? std::max(minShapeScore, sideMinShapeScore)
			           : minShapeScore;
		}
		/** max_stages: only the first this many stages of the cascade are
		 * evaluated (0: all): a looser detector, whose false alarms the
		 * shape check rejects; also for collecting shape-model samples. */
		int maxStages = 0;
		/** segment_candidates: every 3D segment of the object points at
		 * most max_top_m + proposal_top_margin_m high (ObjectProposals
		 * regions, segment_range_gap_m apart) is also a candidate, measured
		 * and shape-checked as the cascade's boxes are: objects the window
		 * search misses or boxes badly still get a candidate. */
		bool segmentCandidates = false;
		/** cascade_support: the shape model also sees how many of the
		 * class's cascade windows cover a candidate
		 * (Candidate::cascadeSupport); false: it sees 0. */
		bool cascadeSupport = false;
		/** back_wall_length_m: a wall at least this long behind the
		 * object's points (BackWall) is cut off before it is measured; 0:
		 * none. */
		double backWallLength = 0;
		/** max_continuing_share: rejected ("taller") when more than this
		 * share of the object's columns continue upwards in the sweep
		 * (continuingShare(): the lower part of a cabinet or a pillar whose
		 * upper part the rules call wall); 1: no check. */
		double maxContinuingShare = 1;
		/** max_overhead_share: rejected ("under something") when more
		 * than this share of the object's columns have something over it
		 * (overheadShare(): a pot's foliage); 1: no check. */
		double maxOverheadShare = 1;
		/** min_flat_face_share: rejected ("round") when less than this
		 * share of the front of the object's top band runs along the faces
		 * of one box (flatFaceShare(): a basin's slab has flat faces, a
		 * plant's foliage a round one); 0: no check. */
		double minFlatFaceShare = 0;
		/** min_separation_m: accepted detections of the class whose
		 * centroids are closer than this (horizontally) are one object
		 * (boxes on two parts of a flight of stairs): the one with the
		 * highest shape score, then the most neighbours, then points, stays
		 * (as among duplicates) and its box and pixels take in the others'
		 * (its centroid and extent stay its own); 0: no check. */
		double minSeparation = 0;
		/** grow_m: an accepted detection's object is measured again in
		 * its box grown by this (m, at its range) on every side, over the
		 * points within its own horizontal ranges (not connected to it in
		 * 3D): a flight whose candidate held a part of it, beside an
		 * occluder or cut by a range jump, gets the whole flight's box and
		 * pixels (its centroid and extent stay its own), unless the grown
		 * object is too wide or too high for the class; 0: not grown. */
		double grow = 0;
	};

	/** INI section [CascadeDetector] plus one [CascadeDetector.<label>]
	 * per class listed in `classes`. */
	struct TOptions : public mrpt::config::CLoadableOptions
	{
		TOptions();
		void loadFromConfigFile(
		    const mrpt::config::CConfigFileBase& c,
		    const std::string& section) override;
		void saveToConfigFile(
		    mrpt::config::CConfigFileBase& c,
		    const std::string& section) const override;
		static const std::vector<std::string>& knownKeys();
		/** Loads [section] and its class sections from an INI file and
		 * sets baseDir to the file's directory. Throws ConfigError. */
		static TOptions fromIniFile(
		    const std::string& path,
		    const std::string& section = "CascadeDetector");
		/** The range gate of class `c` (range_scales) for an image whose
		 * pixels are `step` rad apart, upscaled by `upscale`. */
		RangeGate rangeGate(
		    const TClassOptions& c, double step, double upscale) const;
		/** The class options of `l`; throws ConfigError if not listed. */
		const TClassOptions& classOptions(Label l) const;
		/** Resolves a class's cascade path against baseDir. */
		std::string cascadePath(const TClassOptions& c) const;
		/** A path relative to baseDir (absolute paths unchanged). */
		std::string resolvePath(const std::string& file) const;
		/** ObjectProposals::Params of these options (floor tolerance,
		 * height, size) with a join radius and a range gap: the proposals'
		 * (proposal_join_px, proposal_range_gap_m) or the segments'. */
		ObjectProposals::Params proposalParams(
		    int joinRadius, double rangeGap) const;
		/** The segments' (segment_candidates) ObjectProposals::Params:
		 * join radius 1, segment_range_gap_m. */
		ObjectProposals::Params segmentParams() const
		{
			return proposalParams(1, segmentRangeGap);
		}
		/** How high above the ground class `c`'s proposals and segments
		 * reach (max_top_m + proposal_top_margin_m). */
		double proposalTop(const TClassOptions& c) const
		{
			return c.maxTop + proposalTopMargin;
		}
		/** The channel a class's cascade sees. */
		DetectionChannel channelOf(const TClassOptions& c) const
		{
			return c.channel ? *c.channel : channel;
		}

		/** channel: grey, red, green, blue or view (DetectionImage). */
		DetectionChannel channel = DetectionChannel::Grey;
		/** normal_smoothing_px: half width of the normal averaging before
		 * the image is made (DetectionImage), 0 = none. */
		int normalSmoothing = 1;
		/** projection: "panoramic" (azimuth x elevation,
		 * PanoramicProjection) or "sweep" (the sweep's own rows and
		 * columns, as the paper). */
		bool panoramic = true;
		/** classes: labels with a cascade (space separated). */
		std::vector<TClassOptions> classes;
		/** label_pixels: the object points of a detection get its label in
		 * LabeledSweep::labels. */
		bool labelPixels = true;
		/** floor_tolerance_m: points this close to the ground are floor,
		 * not object. */
		double floorTolerance = 0.04;
		/** measure_margin: the object is measured in its box grown by this
		 * fraction of the box side on every side. */
		double measureMargin = 0.5;
		/** connected_object: the object is the candidate points connected
		 * (in the sweep, without a gap in 3D) to those of the box's centre,
		 * so that a box cutting an object still measures all of it. */
		bool connectedObject = true;
		/** proposals: search only windows around object proposals
		 * (ObjectProposals: regions the rule classifier left to objects),
		 * at the window sizes an object of the class can have at the
		 * region's range; false: every window of every pass (the paper's
		 * whole-image search). */
		bool proposals = false;
		/** proposal_min_pixels, proposal_join_px, proposal_max_height_m:
		 * ObjectProposals::Params (minPixels, joinRadius, maxHeight). */
		int proposalMinPixels = 10;
		int proposalJoinPx = 2;
		double proposalMaxHeight = 2.0;
		/** proposal_margin: a proposal's search window is its box grown by
		 * this fraction of the largest window side searched there (capped
		 * at the box's larger side) on every side. */
		double proposalMargin = 0.5;
		/** proposal_size_slack: the window sides expected from the class's
		 * real size (min_width_m .. 1.15 x max(max_width_m, max_top_m)) and
		 * the region's range (near and far percentile) are widened by this
		 * factor both ways. */
		double proposalSizeSlack = 1.15;
		/** proposal_foot_height_m: a proposal whose lowest points are at
		 * most this high above the ground shows an object whole (its foot
		 * is seen): min_size_m applies, else min_cut_size_m. */
		double proposalFootHeight = 0.1;
		/** proposal_fill: a proposal is taken to be (mostly) one object,
		 * which fills at least this fraction of the proposal's larger side:
		 * no smaller windows are searched there (0: any size down to the
		 * class's smallest at the proposal's range). */
		double proposalFill = 0.5;
		/** proposal_range_gap_m: neighbouring object pixels whose ranges
		 * differ by more than this (+ 5 % of the range) start another
		 * proposal (ObjectProposals::Params::rangeGap). */
		double proposalRangeGap = 1.0;
		/** proposal_top_margin_m: a class's proposals are the regions of
		 * the object points at most max_top_m + this above the ground
		 * (ObjectProposals::find). */
		double proposalTopMargin = 0.1;
		/** proposal_size_check: skip a proposal whose real size cannot
		 * hold an object of the class (its top below min_top_m, narrower
		 * than min_width_m, or wider than max_width_m / proposal_fill;
		 * with proposal_size_slack). */
		bool proposalSizeCheck = true;
		/** range_scales: the whole-image search evaluates a window only
		 * at the scales the range at its centre allows: the object it
		 * would hold (window side / 1.15, as the training window is the
		 * object's larger side + 15 %) must be between min_cut_size_m /
		 * range_scale_slack and max_size_m x range_scale_slack (the 20 x 20
		 * cascade window spans 20 pixels of `step` rad, so a metric size
		 * fixes its pixel size). Windows whose centre has no range are
		 * skipped. Runs the project's CascadeEvaluator over the pyramid as
		 * detectMultiScale does (same levels, steps, grouping). false:
		 * detectMultiScale on every window. */
		bool rangeScales = false;
		/** range_scale_slack: widens the allowed object size both ways. */
		double rangeScaleSlack = 1.3;
		/** range_cut_m: closer than this an object may be cut by the lowest
		 * tilt line (min_cut_size_m applies instead of min_size_m). */
		double rangeCut = 2.0;
		/** range_objects_only: windows are searched only around the points
		 * the rule classifier left to objects (ObjectProposals::objectMask,
		 * at most max_top_m + proposal_top_margin_m high): one of the five
		 * range samples must be such a point. */
		bool rangeObjectsOnly = false;
		/** segment_range_gap_m: neighbouring object pixels (8-connected)
		 * whose horizontal ranges differ by more than this (+ 5 % of the
		 * range) are in different segments (segment_candidates). */
		double segmentRangeGap = 0.15;
		/** segment_max_taller: a segment joined by more higher object
		 * pixels than this fraction of its own (ObjectProposal::
		 * tallerPixels) is the lower part of something taller, not a
		 * candidate. */
		double segmentMaxTaller = 0.1;
		/** segment_range_window: a segment candidate is measured over its
		 * own horizontal range only (ObjectProposal::nearRange ..
		 * farRange, widened by segment_range_gap_m + 5 % each way): a
		 * chair before a flight or the wall behind a basin, at other
		 * ranges, does not join it. */
		bool segmentRangeWindow = true;
		/** threads: classes (and a class's range-gated passes) searched,
		 * and candidates measured, in parallel on up to this many threads
		 * (0: all cores, 1: the calling thread only); the same candidates
		 * either way. */
		int threads = 1;
		/** Directory relative cascade paths are resolved against. */
		std::string baseDir = ".";
	};

	/** A detection's 3D measurement (robot frame). */
	struct Measure
	{
		std::size_t points = 0;
		double width = 0, top = 0;
		mrpt::math::TPoint3D centroid{0, 0, 0}, extent{0, 0, 0};
		/** Sweep pixels (x = col, y = row) of the object points and their
		 * bounding box. */
		std::vector<cv::Point> pixels;
		cv::Rect box;
	};
	/** A cascade detection and what became of it. */
	struct Candidate
	{
		Label label = Label::Unknown;
		/** In detection-image coordinates (panoramic or sweep). */
		cv::Rect box;
		int neighbours = 0;
		/** A 3D segment (segment_candidates), not a cascade box. */
		bool fromSegment = false;
		/** The horizontal ranges its object points may have (m;
		 * rangeHi 0: any), segment_range_window. */
		double rangeLo = 0, rangeHi = 0;
		/** Raw cascade windows of its class on it: the neighbours (at
		 * least 1 each) of the class's cascade boxes with IoU >= 0.3 with
		 * its box (ObjectShape::kCascadeSupport). */
		int cascadeSupport = 0;
		std::optional<Measure> measure;
		/** flatFaceShare() of its object, when min_flat_face_share asked
		 * for it and it could be measured. */
		std::optional<double> flatFaceShare;
		bool accepted = false;
		std::string rejection;
		/** Its ObjectShape and the shape model's score, when its class has
		 * a shape model (or describeShapes() is on) and it passed the size
		 * check. */
		std::optional<ObjectShape::Features> shape;
		double shapeScore = 1;
	};
	/** Times of the last detect(), ms: `image` the detection images,
	 * `proposals` the object proposals or the range images of
	 * range_scales, `cascades` and `sizeCheck` (measuring and the shape
	 * check), each summed over its tasks, which may run in parallel;
	 * `total` wall-clock. */
	struct Timings
	{
		double image = 0, proposals = 0, cascades = 0, sizeCheck = 0, total = 0;
	};

	/** Loads every class's cascade (CascadeXml validates it, then
	 * cv::CascadeClassifier). Throws CascadeError or ConfigError. */
	explicit CascadeDetector(const TOptions& options);
	~CascadeDetector();

	/** Runs every class on a perceived sweep (uses the sweep's bearing and
	 * tilt grid and the perceived normals, normal mask, points and ground
	 * height), appends the accepted detections to `out.detections` (box =
	 * the bounding box of the object's pixels in the sweep) and, with
	 * label_pixels, labels their object pixels. */
	void detect(const Sweep& sweep, LabeledSweep& out);

	/** The same on raw inputs; returns every candidate (accepted or not).
	 * `points` CV_32FC3 robot frame (NaN where invalid); `labels` (CV_8U
	 * rule-classifier labels, may be empty): pixels already labelled as a
	 * surface (floor, ceiling, wall, door, sidewalk, grass) are not object
	 * points; `areaIds` (CV_32S segmentation areas, may be empty) tell the
	 * object proposals which surface areas reach above an object's
	 * height (ObjectProposals). */
	std::vector<Candidate> detectCandidates(
	    const std::vector<double>& phis, const std::vector<double>& thetas,
	    const cv::Mat& normals, const cv::Mat& normalMask,
	    const cv::Mat& points, double groundZ,
	    const cv::Mat& labels = cv::Mat(), const cv::Mat& areaIds = cv::Mat());
	/** What the cascades (and the segment candidates) search in one
	 * sweep: prepareSearch(). */
	struct SearchInput
	{
		/** The detection image of each channel in use. */
		std::map<DetectionChannel, cv::Mat> images;
		/** range_scales: per class, the gate's range image (gateRanges();
		 * empty: the class searches every window). */
		std::vector<cv::Mat> ranges;
		/** segment_candidates: per class, its object segments. */
		std::vector<std::vector<ObjectProposal>> segments;
		/** Rad per detection-image pixel: the grid's mean step, and the
		 * one the search uses (0 without range_scales or proposals). */
		double pixelAngle = 0, step = 0;
	};
	/** One class's cascade boxes (detection-image pixels, grouped as
	 * detectMultiScale) with their neighbour counts, in pass order, and
	 * the time its passes took (ms, summed). */
	struct CascadeBoxes
	{
		std::vector<cv::Rect> boxes;
		std::vector<int> neighbours;
		double ms = 0;
	};
	/** The first step of detectCandidates() (same inputs): the detection
	 * images, the range gate's range images, the object proposals and,
	 * `withSegments`, the segments; sets lastTimings().image and
	 * .proposals. */
	SearchInput prepareSearch(
	    const std::vector<double>& phis, const std::vector<double>& thetas,
	    const cv::Mat& normals, const cv::Mat& normalMask,
	    const cv::Mat& points, double groundZ, const cv::Mat& labels,
	    const cv::Mat& areaIds, bool withSegments = true);
	/** The cascades' search alone, as detectCandidates() runs it (range
	 * gate, passes, threads), on a prepareSearch() of this detector: each
	 * class's boxes, before any 3D check. Sets lastTimings(): cascades,
	 * sizeCheck 0, total the preparation's times plus the search's. */
	std::vector<CascadeBoxes> searchCascades(const SearchInput& in);

	/** The image the cascades see (8-bit, panoramic or sweep layout), in
	 * the [CascadeDetector] channel or in `channel`. */
	cv::Mat detectionImage(
	    const std::vector<double>& phis, const std::vector<double>& thetas,
	    const cv::Mat& normals, const cv::Mat& normalMask,
	    std::optional<DetectionChannel> channel = std::nullopt);
	/** The same from normals already smoothed
	 * (DetectionImage::smoothNormals with normal_smoothing_px), in
	 * `channel`; the view rotation and the projection are kept for the
	 * next sweep of the same grid. */
	cv::Mat detectionImage(
	    const std::vector<double>& phis, const std::vector<double>& thetas,
	    const cv::Mat& smoothed, const cv::Mat& normalMask,
	    DetectionChannel channel);
	/** The projection of the last grid used (empty in sweep mode). */
	const PanoramicProjection& projection() const;
	/** Runs one class's cascade on a detection image; boxes in its pixels,
	 * with detectMultiScale's neighbour counts. With `proposals` (detection
	 * image pixels) and `step` (rad per detection-image pixel), only the
	 * searchRegions() of each pass are searched; without, every window,
	 * or with range_scales and a `range` image (CV_32F, horizontal range
	 * of each detection-image pixel, 0 where none) and `step`, every
	 * window at the scales its centre's range allows. `pass` >= 0: only
	 * that one of the class's passes (a range-gated pass may run beside
	 * the class's others). */
	void runCascade(
	    std::size_t classIndex, const cv::Mat& detectionImage,
	    std::vector<cv::Rect>& boxes, std::vector<int>& neighbours,
	    const std::vector<ObjectProposal>* proposals = nullptr, double step = 0,
	    const cv::Mat& range = cv::Mat(), int pass = -1);

	/** Where one pass searches around proposals: an image region and the
	 * range of window sides (detection-image pixels). */
	struct SearchRegion
	{
		cv::Rect rect;
		double minSide = 0, maxSide = 0;
	};
	/** The regions of pass `pass` of class `k` (cascade window `window`)
	 * around `proposals` in an image of `imageSize` whose pixels are `step`
	 * rad apart: per proposal, the window sides an object of the class's
	 * real size can have at the proposal's range (within the pass's
	 * range), and the proposal's box grown by proposal_margin; overlapping
	 * regions are merged. */
	std::vector<SearchRegion> searchRegions(
	    const TClassOptions& k, const DetectionPass& pass, cv::Size window,
	    const std::vector<ObjectProposal>& proposals, cv::Size imageSize,
	    double step) const;
	/** The proposals of the last detectCandidates() call, per class (in
	 * the order of TOptions::classes). */
	const std::vector<std::vector<ObjectProposal>>& lastProposals() const;

	/** Measures the object among `pixels` (sweep pixels of a detection
	 * box, grown): the points that are not floor (within floorTolerance of
	 * the ground) nor labelled as a surface in `labels` (if not empty),
	 * within max_depth_m (horizontally) behind the nearest part (10th
	 * percentile) of those among `centre` (the box's central half) and,
	 * with `connected`, connected to those of the centre; without the
	 * points on or behind a BackWall at least `backWallLength` long (0:
	 * none), and with `rangeHi` > 0 only the points whose horizontal range
	 * is within [rangeLo, rangeHi]; nothing when fewer than min_points. */
	static std::optional<Measure> measure(
	    const cv::Mat& points, const cv::Mat& labels,
	    const std::vector<cv::Point>& pixels,
	    const std::vector<cv::Point>& centre, double groundZ,
	    double floorTolerance, double maxDepth, int minPoints,
	    bool connected = false, double backWallLength = 0, double rangeLo = 0,
	    double rangeHi = 0);

	/** The share of the measured object's columns (sweep pixels
	 * `m.pixels`, row 0 lowest) whose highest point continues upwards: a
	 * point at most 3 rows above it, at least 2 cm higher, closer in 3D
	 * than measure()'s connection gap and not labelled ceiling in `labels`
	 * (may be empty). 0 for an object with nothing on top of it. */
	static double continuingShare(
	    const cv::Mat& points, const cv::Mat& labels, const Measure& m);

	/** The share of the measured object's columns with a point above its
	 * top that overhangs it: higher than its top by 3 cm to kOverheadReach,
	 * not labelled ceiling in `labels` (may be empty), nearer to the sensor
	 * (horizontally) than the object's front by 2 cm, and at most
	 * kOverheadReach / 2 beyond its half width from its centroid. A plant's
	 * foliage, wider than its pot, is such a thing; the wall behind a
	 * wastebasket is not. `groundZ`: the floor's height in the points'
	 * frame. */
	static double overheadShare(
	    const cv::Mat& points, const cv::Mat& labels, const Measure& m,
	    double groundZ);
	/** How far above and in front of an object overheadShare() looks, m. */
	static constexpr double kOverheadReach = 0.8;

	/** The share of the measured object's front, in its top band (the
	 * kFlatFaceBand highest metres of it; `groundZ` the floor's height),
	 * that runs along the faces of one box: its direction between points
	 * kFlatFaceBaseline apart lies within kFlatFaceToleranceDeg of one
	 * direction or of one at 90 deg to it, the direction that holds the
	 * most. The front of a column (sweep pixels `m.pixels`) is the median
	 * of its band's points within 2 cm of its nearest. A box's faces give
	 * about 1, also seen across a corner; a cylinder's round front spreads
	 * the directions (0.3-0.5). nullopt when fewer than
	 * kFlatFaceMinSegments directions are measured. */
	static std::optional<double> flatFaceShare(
	    const cv::Mat& points, const Measure& m, double groundZ);
	/** flatFaceShare()'s band (m below the top), baseline (m), angle
	 * tolerance (deg) and fewest directions. */
	static constexpr double kFlatFaceBand = 0.1;
	static constexpr double kFlatFaceBaseline = 0.06;
	static constexpr double kFlatFaceToleranceDeg = 15;
	static constexpr int kFlatFaceMinSegments = 4;

	/** The range-gated search evaluates windows with AVX2 where the CPU has
	 * it (default) or, with false, with the portable loop: the same
	 * candidates either way (CascadeEvaluator::setSimd); for benchmarks and
	 * checks. */
	void setSimd(bool on);
	/** Describe every candidate that passes the size check
	 * (Candidate::shape) even for classes without a shape model: for
	 * training shape models. */
	void describeShapes(bool on);

	const TOptions& options() const { return m_options; }
	const Timings& lastTimings() const { return m_timings; }

private:
	/** The cascades' search on `in` in one parallel step (threads) with
	 * `extraTasks` more tasks, extra(0 .. extraTasks - 1), beside it. */
	std::vector<CascadeBoxes> runSearch(
	    const SearchInput& in, std::size_t extraTasks,
	    const std::function<void(std::size_t)>& extra);
	/** Keeps the grid's elevations, view rotation (when `view`) and
	 * projection for the images of this grid. */
	void prepareGrid(
	    const std::vector<double>& phis, const std::vector<double>& thetas,
	    cv::Size sweepSize, bool view);
	/** A detection image of the prepared grid. */
	cv::Mat gridImage(
	    const cv::Mat& smoothed, const cv::Mat& normalMask,
	    DetectionChannel channel) const;
	/** range_scales: per class, the horizontal range of the pixels whose
	 * windows are searched (0 elsewhere), in detection-image layout;
	 * `mask` the sweep's ObjectProposals::objectMask (range_objects_only)
	 * or empty. */
	std::vector<cv::Mat> gateRanges(
	    const cv::Mat& points, const cv::Mat& mask, double groundZ) const;
	/** segment_candidates: per class, the 3D segments of its object points
	 * (`objects`, the sweep's ObjectProposals::objectMask; none for classes
	 * without segment candidates), in detection-image layout. */
	std::vector<std::vector<ObjectProposal>> objectSegments(
	    const cv::Mat& points, const cv::Mat& objects, double groundZ) const;
	/** grow_m: `c` (accepted, class `k`) measured again in its sweep box
	 * grown by k.grow at its range (`step` rad per pixel); its box and
	 * pixels become what that finds unless it is too wide or high. */
	void growObject(
	    Candidate& c, const TClassOptions& k, const cv::Mat& points,
	    const cv::Mat& labels, double groundZ, double step) const;

	/** runCascade() on one pass: around `proposals`, or over the pass's
	 * band (range-gated with range_scales and a `range` image). */
	void searchProposals(
	    std::size_t classIndex, const DetectionPass& pass, const cv::Mat& image,
	    const std::vector<ObjectProposal>& proposals, double step,
	    std::vector<cv::Rect>& boxes, std::vector<int>& neighbours);
	void searchBand(
	    std::size_t classIndex, std::size_t passIndex,
	    const DetectionPass& pass, const cv::Mat& image, const cv::Mat& range,
	    double step, std::vector<cv::Rect>& boxes,
	    std::vector<int>& neighbours);

	/** The sweep detectCandidates() works on. */
	struct SweepImages
	{
		const cv::Mat& normals;
		const cv::Mat& normalMask;
		const cv::Mat& points;
		const cv::Mat& labels;
		double groundZ = 0;
	};
	/** segment_candidates: per class, its segments that may be objects,
	 * and (class, index) of each. */
	void segmentCandidates(
	    const SearchInput& in, std::vector<std::vector<Candidate>>& cands,
	    std::vector<std::pair<std::size_t, std::size_t>>& tasks) const;
	/** Measures candidate `c` of class `classIndex` in the box grown by
	 * measure_margin, checks its size and describes it (with its cascade
	 * support as it is then); returns the time taken (ms). */
	double measureCandidate(
	    std::size_t classIndex, Candidate& c, const SweepImages& sweep) const;
	/** A class's candidates: its cascade boxes, then its `segments` (moved
	 * from), each with the cascade support of the boxes overlapping it. */
	std::vector<Candidate> classCandidates(
	    std::size_t classIndex, const CascadeBoxes& found,
	    std::vector<Candidate>& segments) const;
	/** The shape check and the suppression of duplicates on a class's
	 * measured candidates, then grow_m. */
	void finishCandidates(
	    std::size_t classIndex, std::vector<Candidate>& cands,
	    const SweepImages& sweep, double pixelAngle) const;

	struct Impl;
	TOptions m_options;
	std::unique_ptr<Impl> m_impl;
	Timings m_timings;
};

}  // namespace semnav
