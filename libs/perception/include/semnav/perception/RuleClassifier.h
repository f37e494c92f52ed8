/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/system/COutputLogger.h>
#include <semnav/perception/LabeledSweep.h>
#include <semnav/perception/NormalImage.h>
#include <semnav/perception/Roughness.h>

#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

namespace semnav
{
/** The paper's rule-based identification of uniform areas (sec. 2.2.1):
 * floor, ceiling, wall, door, sidewalk, grass and obstacle.
 *
 * 1. Orientation per pixel from the normals averaged over 3 x 3 pixels:
 *    up, down, vertical, oblique, none.
 * 2. Ground level: the lowest well-supported height of up-facing pixels
 *    (or ground_z_m): "floor has z equal to the ground level". On a sweep
 *    whose frame stands on the floor (classify()'s floorReferenced), only
 *    within ground_search_m of ground_z_m: where a near flight of stairs
 *    hides the floor, its treads are not the ground.
 * 3. Surfaces. Floor, walls and ceiling flood into one area (the paper
 *    says so; in fact everything standing on the floor does), so areas
 *    are split into surfaces: 4-connected pixels of one area and
 *    orientation with continuous ranges, vertical and oblique ones also
 *    with normals close to the neighbour's and to the surface's running
 *    mean (a corner must not chain two walls). Vertical surfaces that lie
 *    on one plane are grouped across areas (a wall seen at a grazing angle
 *    floods into column strips), and a group is split where its plane
 *    steps by plane_split_offset_m (a door recessed in its wall: dominant
 *    plane by RANSAC, smoothed residuals, Otsu). A smaller step
 *    (door_seam_split_offset_m) splits along seams, or with
 *    door_shape_split where one side, after refitting the plane on the
 *    wall, is a leaf-shaped box under the other. Looser groups (one wall
 *    within wall_group_tolerance_m) serve the wall size rule.
 * 4. Rules on each surface (size, orientation, topology; thresholds in
 *    config/perception.ini):
 *    - ground: up-facing, mean height within ground_tolerance_m of the
 *      ground level;
 *    - ceiling: down-facing, at least ceiling_min_height_m above ground;
 *    - wall: vertical and tall (wall_min_height_m; from the ground when
 *      the field of view cuts its bottom), reaching the ceiling, or long
 *      (wall_min_length_m) and reaching wall_long_min_reach_m above the
 *      ground (a low garden wall is an obstacle), itself or with its wall
 *      group; one narrower than wall_min_width_m only when tall or
 *      reaching the ceiling (the end face of a wall at an opening);
 *    - door: one vertical surface door_min/max_width_m wide,
 *      door_min/max_height_m high, bottom at the ground, with walls
 *      parallel and within door_max_offset_m of its plane on its left,
 *      right and top in the image (the paper's "connects directly to a
 *      floor at its bottom and to a wall from all other sides"), standing
 *      off them by door_min_offset_m. A side cut by the field of view (the
 *      surface reaches the image border there) is accepted in place of a
 *      wall, and its extent there in place of the size, when
 *      door_allow_truncation; one side must still be a wall. With
 *      door_lintel_one_side, walls above it and on one side suffice (the
 *      other side hidden by a reveal, a corner, or a far wall behind).
 *      A side (left, right, bottom) whose neighbours are nearer to the
 *      sensor by door_occlusion_margin_m is hidden: its width or bottom
 *      there is a lower bound, as where the field of view cuts it;
 *    - obstacle: any other surface reaching above the ground; a piece
 *      lying on an adjacent wall's plane is left to step 5 instead.
 * 5. Pixels left over (surface edges, oblique or missing normals, small
 *    areas) join a neighbouring labelled surface when they lie on its plane
 *    (or in its area, for obstacles), else by height: ground level ->
 *    ground, above -> obstacle. The paper leaves small areas out; this step
 *    (classify_leftover_pixels) labels them for pixel-level scoring.
 * 6. Ground: floor when indoor (a ceiling seen, or environment = indoor);
 *    outdoors each w' x w' square of ground is sidewalk when its R-bar >=
 *    sidewalk_min_rbar, else grass; squares without R-bar (far ground, no
 *    normals) by the spread of their heights (sidewalk_max_height_std_m);
 *    the rest take their nearest neighbour's type; patches under
 *    min_patch_squares are absorbed. Off as shipped (they move the outdoor
 *    localizer): squares grass by R-bar whose heights spread at most
 *    sidewalk_flat_max_height_std_m are sidewalk (R-bar is noise where the
 *    rows nearly coincide, at the sweep's sides), and on the sidewalk /
 *    grass border each pixel is typed by the mean R of the window centred
 *    on it (sidewalk_border_half_width_px), not by its square.
 *
 * classify() runs on the images of a NormalImage, the areas of a
 * RangeSegmentation and a Roughness; buffers are reused between calls. */
class RuleClassifier : public mrpt::system::COutputLogger
{
public:
	/** INI section [RuleClassifier]. Angles are configured in degrees and
	 * stored in radians. */
	struct TOptions : public mrpt::config::CLoadableOptions
	{
		void loadFromConfigFile(
		    const mrpt::config::CConfigFileBase& c,
		    const std::string& section) override;
		void saveToConfigFile(
		    mrpt::config::CConfigFileBase& c,
		    const std::string& section) const override;

		enum class Environment
		{
			Auto,
			Indoor,
			Outdoor
		};

		// Orientation
		int normalSmoothingHalfWidth = 1;
		double groundNormalTolerance = 30.0 * M_PI / 180;
		double ceilingNormalTolerance = 20.0 * M_PI / 180;
		double wallNormalTolerance = 20.0 * M_PI / 180;
		double surfaceJoinAngle = 20.0 * M_PI / 180;
		double surfaceMaxAngle = 25.0 * M_PI / 180;
		double surfaceMaxRangeStep = 0.05;
		int minSurfacePixels = 30;
		double planeMergeTolerance = 0.01;
		double planeMergeAngle = 10.0 * M_PI / 180;
		double planeSplitOffset = 0.012;
		double wallGroupTolerance = 0.05;
		double wallGroupAngle = 15.0 * M_PI / 180;
		int planeSplitHalfWidth = 2;
		// Ground and ceiling
		bool autoGroundLevel = true;
		double groundZ = 0.0;
		double groundTolerance = 0.10;
		double groundSearch = 0.10;
		int minGroundPixels = 200;
		double ceilingMinHeight = 1.8;
		Environment environment = Environment::Auto;
		int indoorMinCeilingPixels = 500;
		// Wall
		double wallMinHeight = 1.9;
		double wallCeilingGap = 0.3;
		double wallMinLength = 2.5;
		double wallMinWidth = 0.1;
		double wallLongMinReach = 1.4;
		// Door
		double doorMinWidth = 0.7, doorMaxWidth = 2.0;
		/** door_framed_max_width_m: a surface wider than doorMaxWidth and at
		 * most this wide is a door only with wall found on its left, right
		 * and top, none cut by the field of view (0 = off). */
		double doorFramedMaxWidth = 2.3;
		double doorMinHeight = 1.5, doorMaxHeight = 2.5;
		double doorBottomTolerance = 0.2;
		double doorMaxOffset = 0.15;
		double doorMaxAngle = 15.0 * M_PI / 180;
		double doorMinOffset = 0.003;
		/** A candidate with wall along at least doorFramedSideFraction of
		 * its left, right and top, none cut by the field of view, needs to
		 * stand off them by this only (m): a nearly flush leaf framed all
		 * round. */
		double doorFramedMinOffset = 0.002;
		double doorFramedSideFraction = 0.9;
		bool doorAllowTruncation = true;
		int doorSearchPixels = 6;
		double doorSearchDistance = 0.15;
		double doorSearchMinSize = 0.3;
		double doorSeamSplitOffset = 0.003;
		double doorSeamDepth = 0.015;
		double doorSeamMinHeight = 1.0;
		int doorSeamMinNotches = 8;
		double doorSeamMinShare = 0.5;
		double doorMinSideFraction = 0.5;
		double doorSingleSideFraction = 0.8;
		bool doorLintelOneSide = true;
		double doorOcclusionMargin = 0.05;
		bool doorShapeSplit = true;
		bool doorLintelSplit = true;
		/** door_lintel_after_cut: after a group is cut at a plane step
		 * (plane_split_offset_m, or between seams), each side is searched
		 * again for a leaf under its lintel (door_lintel_split). */
		bool doorLintelAfterCut = true;
		/** door_lintel_3d: a leaf cut by the field of view whose probes
		 * find a wall above it in 3D along door_min_side_fraction of its
		 * width (seen close up, its lintel lies beside it in the image). */
		bool doorLintel3d = true;
		/** door_recessed_leaf_offset_m: a leaf seen close up beside the
		 * robot, cut by the field of view at its top, bottom and one side,
		 * is a door when its other side finds walls of its plane along
		 * door_recessed_leaf_side_fraction and it stands off them by this
		 * much (recessed in its frame; 0 = off). */
		double doorRecessedLeafOffset = 0.05;
		double doorRecessedLeafSideFraction = 0.15;
		/** door_recessed_frame_side_fraction: a leaf standing off its walls
		 * by door_recessed_leaf_offset_m, none of its sides cut by the
		 * field of view, is a door with walls found along this share of
		 * its left, right and top each (0 = off). */
		double doorRecessedFrameSideFraction = 0.35;
		/** door_framed_min_width_m: a candidate narrower than
		 * door_min_width_m but at least this wide, cut by the field of view
		 * at its bottom (seen close up), is a door when walls hold along
		 * door_single_side_fraction of its left, right and top, none cut by
		 * the field of view (a leaf of which a piece was cut out; 0 = off). */
		double doorFramedMinWidth = 0.3;
		// Ground type (outdoor)
		double sidewalkMinRbar = 0.97;
		double sidewalkMaxHeightStd = 0.012;
		int minPatchSquares = 4;
		// The border per pixel and the flat squares (docs/perception.md).
		int sidewalkBorderHalfWidth = 2;
		double sidewalkFlatMaxHeightStd = 0.007;
		// Leftover pixels
		double leftoverPlaneTolerance = 0.05;
		bool classifyLeftoverPixels = true;
		/** wall_plane_reclaim_m: pixels labelled obstacle that are
		 * 4-connected to a wall through pixels within this distance of
		 * that wall's plane become wall (0: off; docs/perception.md,
		 * "Wall plane reclaim"). */
		double wallPlaneReclaimTolerance = 0.03;
		/** wall_plane_reclaim_ceilings: ceiling surfaces reclaim the
		 * obstacle pixels on their planes too. */
		bool wallPlaneReclaimCeilings = true;
	};

	RuleClassifier();
	explicit RuleClassifier(const TOptions& options);

	/** Labels the sweep from normals.classifierNormals(). `areaIds` from
	 * RangeSegmentation; `roughness` computed on the same normals and
	 * areas (its square width is w').
	 * Fills out.labels, regionIds, regions, groundZ, ceilingZ, indoor;
	 * the other images of `out` are left untouched. `floorReferenced`: the
	 * points' frame stands on the floor (the robot's; false for a frame at
	 * the sensor, whose height is unknown). */
	void classify(
	    const NormalImage& normals, const cv::Mat& areaIds,
	    const Roughness& roughness, LabeledSweep& out,
	    bool floorReferenced = false);

	const TOptions& options() const { return m_options; }

	/** Surfaces of the last classify() call (step 3), CV_32S, -1 = none; a
	 * view of internal memory, valid until the next call. For debugging
	 * and tests. */
	cv::Mat surfaceIds() const;
	/** Orientation class of the last call's pixels (0 none, 1 up, 2 down,
	 * 3 vertical, 4 oblique), CV_8U view; for debugging and tests. */
	cv::Mat orientationClasses() const;
	/** Smoothed residuals to the plane of their coplanar group (m, CV_32F,
	 * 0 outside split candidates) and the side of the step each pixel is
	 * on (CV_8U); views, for debugging and tests. */
	cv::Mat planeResiduals() const { return m_resSum; }
	cv::Mat planeSides() const;

private:
	/** A connected piece of one area (pass 1) or of one group of coplanar
	 * pieces (pass 2) with one orientation. */
	struct Surface
	{
		uint8_t orient = 0;
		int area = 0;
		int count = 0;
		cv::Vec3d sumP{0, 0, 0}, sumN{0, 0, 0};
		double sxx = 0, sxy = 0, syy = 0;
		cv::Vec3f minP, maxP;
		int minR = 0, maxR = 0, minC = 0, maxC = 0;
		cv::Vec3d normal{0, 0, 0}, centroid{0, 0, 0};
		double width = 0, height = 0;
		int8_t label = -1;  ///< Label id, -1 = none yet
		double planeD() const { return normal.dot(centroid); }
		/** Adds o's pixel count, sums and bounds (the bounds are o's when
		 * this one is empty). */
		void addStats(const Surface& o);
	};
	/** What the door rule found around a candidate. */
	struct DoorCheck
	{
		double left = 0, right = 0, top = 0;  ///< fraction with a wall
		bool leftFov = false, rightFov = false, topFov = false,
		     bottomFov = false;
		/** Hidden by something in front along door_min_side_fraction of
		 * the side (door_occlusion_margin_m). */
		bool leftHidden = false, rightHidden = false, bottomHidden = false;
		double maxOffset = 0;  ///< largest |offset| to an adjacent wall
		/** Share of the leaf's width (5 cm slices along its plane) under
		 * which a probe found a wall pixel above the leaf's top: its
		 * lintel in 3D, wherever the image puts it. */
		double lintelAbove = 0;
		/** Left, right and top all in view (none cut by the field of
		 * view), each with wall along at least `fraction` of it. */
		bool wholeFrame(double fraction) const
		{
			return !leftFov && !rightFov && !topFov && left >= fraction &&
			       right >= fraction && top >= fraction;
		}
	};

	/** Adjacency of mergeable surfaces (CSR: neighbours of s are
	 * adj[start[s]] .. adj[start[s + 1] - 1]) and those with neighbours,
	 * largest first. */
	struct SurfaceGraph
	{
		std::vector<int> start, adj, order;
	};

	// classify()'s stages, in order (one file each: RuleClassifier*.cpp).
	/** Resets `out`, checks the input, points the working state at it;
	 * false for an empty sweep. */
	bool beginSweep(
	    const NormalImage& normals, const cv::Mat& areaIds, LabeledSweep& out);
	/** Step 1: m_class from the smoothed normals (m_ns). */
	void classifyOrientation(const NormalImage& normals);
	/** Step 2. */
	double estimateGround(bool floorReferenced, bool& estimated) const;
	/** Step 3, pass 1: 4-connected pixels of one area and one orientation,
	 * vertical/oblique ones with close normals. */
	void buildPieces();
	void computeJoinMask();
	/** Numbers the vertical or oblique piece grown from `seed` as `id`. */
	void fillPiece(int seed, int id, float cosSpread2);
	/** Unites adjacent coplanar vertical surfaces (across areas) into
	 * m_parent (one plane) and m_loose (one wall). */
	void mergeCoplanar();
	void collectVerticalPairs(const std::vector<uint8_t>& canMerge);
	SurfaceGraph surfaceGraph(const std::vector<uint8_t>& canMerge) const;
	void groupCoplanar(
	    const SurfaceGraph& graph, double tol, double angle,
	    std::vector<int>& parent) const;
	/** Sets m_side where a vertical group has two planes a step apart. */
	void splitPlanes();
	/** Groups worth examining (their slots; per slot the least-squares
	 * plane); returns the slot per group root, -1 for none. */
	std::vector<int> selectSplitCandidates(
	    std::vector<cv::Vec3d>& normal, std::vector<double>& offset);
	void gatherSlotPixels(const std::vector<int>& slot, int nSlots);
	void splitByResiduals(
	    const std::vector<cv::Vec3d>& normal,
	    const std::vector<double>& offset);
	/** Share of the row crossings between the two sides of slot's step
	 * (smoothed residual `threshold`) with a seam beside them (a pixel off
	 * the plane by door_seam_depth_m, or none); 0 with few crossings. */
	double seamShare(
	    int slot, float threshold, const cv::Vec3d& normal,
	    double offset) const;
	/** Cuts slot's group (plane normal, offset) along vertical seams: a
	 * stretch between seams whose plane steps by door_seam_split_offset_m
	 * (a nearly flush leaf) gets side 1 in m_side; true when one does. */
	bool splitAtSeams(int slot, const cv::Vec3d& normal, double offset);
	/** With door_shape_split: when one side of slot's step (smoothed
	 * residual `threshold`) is a leaf-shaped box (door_search_min_size_m to
	 * door_max_width_m wide, at most door_max_height_m high, from the
	 * group's bottom, under the other side, which also flanks it) that it
	 * fills (kDoorShapeMinPurity), gives the box side 1 in m_side; true
	 * when it does. */
	bool splitDoorShaped(
	    int slot, float threshold, const cv::Vec3d& normal, double offset);
	/** With door_lintel_split: where, below some height, a stretch of
	 * slot's group (door_search_min_size_m to door_max_width_m wide) lies
	 * door_seam_split_offset_m behind or before the same stretch above
	 * that height (a lintel), and the group beside it does not, gives the
	 * stretch below that height side 1 in m_side; true when it does. The
	 * step is measured column by column against the wall above, so a
	 * least-squares plane leaning towards the leaf does not hide it.
	 * With onSide >= 0, only the pixels of that side of a step already cut
	 * (m_side) are looked at, and the stretch gets side 2. */
	bool splitUnderLintel(
	    int slot, const cv::Vec3d& normal, double offset, int onSide = -1);
	/** With door_lintel_after_cut, after slot's group was cut (m_side 0 /
	 * 1): splitUnderLintel() on each side. */
	void splitSidesUnderLintel(
	    int slot, const cv::Vec3d& normal, double offset);
	/** Step 3, pass 2: pixels of one coplanar group (m_parent) and one side
	 * of its plane step. */
	void buildGroupSurfaces();
	void computeSurfaceStats(int count, int firstAccumulated);
	void finishSurface(Surface& s) const;
	static void fitVerticalPlane(Surface& s);
	/** Step 4: labels surfaces; returns the ceiling's pixel count. */
	std::size_t applyRules(double zg, LabeledSweep& out);
	std::size_t labelGroundAndCeiling(
	    double zg, std::vector<uint8_t>& isCeiling, LabeledSweep& out);
	/** Per surface: 1 where the wall size rules hold. */
	std::vector<int> findWalls(const LabeledSweep& out) const;
	void labelDoorsAndWalls(
	    double zg, const std::vector<int>& wallCandidate,
	    const std::vector<uint8_t>& isCeiling);
	/** False when only one side of the door is a wall and it holds along
	 * less than door_single_side_fraction. */
	bool singleSideHolds(const Surface& s, const DoorCheck& dc) const;
	/** True when door_lintel_one_side and s (door_search_min_size_m, its
	 * top not cut by the field of view) has walls above it and on one
	 * side. */
	bool lintelAndOneSide(const Surface& s, const DoorCheck& dc) const;
	/** True when door_lintel_3d and s (door_search_min_size_m) is cut by
	 * the field of view at its top or a side and has a wall above it along
	 * door_min_side_fraction of its width (DoorCheck::lintelAbove). */
	bool lintelSeenIn3d(const Surface& s, const DoorCheck& dc) const;
	/** True when door_recessed_leaf_offset_m > 0 and s
	 * (door_search_min_size_m) is cut by the field of view at its top,
	 * bottom and one side (it fills the image's rows, its top at most
	 * door_max_height_m above the ground zg), its other side finds walls
	 * along door_recessed_leaf_side_fraction and it stands off them by
	 * door_recessed_leaf_offset_m. */
	bool recessedLeafBeside(
	    const Surface& s, const DoorCheck& dc, double zg) const;
	/** True when door_recessed_frame_side_fraction > 0, s stands off its
	 * walls by door_recessed_leaf_offset_m (> 0), none of its left, right
	 * and top is cut by the field of view and walls hold along
	 * door_recessed_frame_side_fraction of each. */
	bool recessedLeafFramed(const DoorCheck& dc) const;
	/** True when door_framed_min_width_m > 0, s is at least that wide,
	 * cut by the field of view at its bottom, and walls hold along
	 * door_single_side_fraction of its left, right and top, none cut by the
	 * field of view. */
	bool narrowAndFramed(const Surface& s, const DoorCheck& dc) const;
	/** True when s shows door_search_min_size_m of its width and height. */
	bool doorSized(const Surface& s) const
	{
		return s.width >= m_options.doorSearchMinSize &&
		       s.height >= m_options.doorSearchMinSize;
	}
	DoorCheck checkDoor(
	    int self, const std::vector<int>& wallCandidate,
	    const std::vector<uint8_t>& isCeiling) const;
	/** Sets res's *Fov flags: where the field of view cuts the door (probes
	 * that ran out of the image: leftB, rightB, topB; its lowest / highest
	 * pixel pLo / pHi at the image border). */
	void markFieldOfViewCuts(
	    const Surface& door, int leftB, int rightB, int topB, int pLo, int pHi,
	    DoorCheck& res) const;
	/** Obstacle pieces lying on an adjacent wall's plane lose their label. */
	void unlabelPlaneFragments();
	/** Step 5: m_label from the surfaces, then the leftover pixels. */
	void labelPixels(double zg);
	void labelSurfacePixels();
	void seedLeftovers();
	void growLeftovers(double zg);
	void reclaimWallPlanes();
	/** Step 6: indoor or outdoor; out.labels; ground types outdoors. */
	void finishLabels(
	    std::size_t ceilPixels, const Roughness& roughness, LabeledSweep& out);
	void labelGroundTypes(const Roughness& roughness, LabeledSweep& out);
	void typeSquaresByHeight(
	    const int* groundMask, int w, int minSquarePixels,
	    std::vector<int8_t>& squareTypes) const;
	void typeFlatSquares(
	    const int* groundMask, int w, int minSquarePixels,
	    std::vector<int8_t>& squareTypes) const;
	/** Per w' x w' square of type squareType with >= minSquarePixels
	 * ground points: the variance of their heights (else -1). */
	std::vector<double> squareHeightVariances(
	    const int* groundMask, int w, int minSquarePixels,
	    const std::vector<int8_t>& squareTypes, int8_t squareType) const;
	void refineGroundBorder(
	    const cv::Mat& r, const int* groundMask, int w,
	    const std::vector<int8_t>& squareTypes, uint8_t* labels);
	void buildRegions(LabeledSweep& out, const cv::Mat& rBar);
	void fillRegion(int seed, int id, const uint8_t* labels, int* regionIds);

	TOptions m_options;
	// Per-call working state (buffers reused between sweeps).
	int m_rows = 0, m_cols = 0;
	const cv::Mat* m_points = nullptr;
	const cv::Mat* m_pointMask = nullptr;
	const cv::Mat* m_ranges = nullptr;
	const cv::Mat* m_areas = nullptr;
	cv::Mat m_smooth, m_smoothSum;
	const cv::Mat* m_ns = nullptr;
	std::vector<uint8_t> m_class;
	std::vector<uint8_t> m_side, m_join;
	/** Per pass-1 surface: root of a group split by splitPlanes(); (pass 2)
	 * the split groups' pixels, row-major. */
	std::vector<uint8_t> m_groupSplit;
	std::vector<int> m_splitPix;
	std::vector<uint64_t> m_pairs;    ///< mergeCoplanar()'s surface pairs
	std::vector<uint8_t> m_seed;      ///< leftover pixels (valid, no label)
	std::vector<uint8_t> m_zeroRow;   ///< zeros beyond the image's rows
	std::vector<int8_t> m_surfLabel;  ///< label per surface id + 1
	/** What a labelled surface takes of the leftover pixels next to it. */
	struct Claim
	{
		enum Kind : int8_t
		{
			kGround,  ///< points at ground level
			kArea,    ///< pixels of its range area (obstacles apart)
			kPlane,   ///< points on its plane
			kNothing  ///< none
		};
		double nx = 0, ny = 0, nz = 0, d = 0;
		int area = 0;
		int8_t kind = kPlane, label = -1;
	};
	std::vector<Claim> m_claim;
	/** splitPlanes()'s sums per group (those the plane fit needs). */
	struct GroupSums
	{
		int count = 0;
		double sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0;
	};
	std::vector<GroupSums> m_groupSums;
	std::vector<int> m_surf, m_group, m_stack, m_parent, m_loose, m_surfLoose,
	    m_uf;
	std::vector<Surface> m_surfaces;
	std::vector<Surface> m_combined;  ///< pass 2's surfaces, swapped in
	/** splitPlanes()' slots (vertical groups examined): their root
	 * surfaces, and their pixels (row-major per slot, slot k from
	 * m_slotStart[k]). */
	std::vector<int> m_slotGroup, m_slotStart, m_slotPix;
	std::vector<uint8_t> m_slotSeamOnly;  ///< too flat for the plain split
	std::vector<float> m_slotX, m_slotY;  ///< their points' x and y
	std::vector<int> m_fillStack;         ///< pass 1's fill stack (n slots)
	std::vector<int> m_finalOf;           ///< pass 2: new id per pass-1 id + 1
	std::vector<int8_t> m_label;
	std::vector<int> m_owner;
	std::vector<int> m_rowOf, m_colOf;
	cv::Mat m_res, m_wt, m_resSum, m_wtSum;
	cv::Mat m_groundR, m_groundN;  // refineGroundBorder
	std::vector<float> m_tmp;
};

}  // namespace semnav
