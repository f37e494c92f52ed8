/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/core/bits_math.h>
#include <semnav/common/Error.h>
#include <semnav/common/OptionTable.h>
#include <semnav/perception/RuleClassifier.h>

#include <string>

namespace semnav
{
namespace
{
using O = RuleClassifier::TOptions;
const OptionTable<O>& optionTable()
{
	static const auto t =
	    OptionTable<O>()
	        .integer(
	            "normal_smoothing_half_width_px", &O::normalSmoothingHalfWidth,
	            0, 10,
	            "Orientation of a pixel from its normal averaged over "
	            "(2k+1)^2 pixels.")
	        .angle(
	            "ground_normal_tolerance_deg", &O::groundNormalTolerance, 0, 89,
	            "Up-facing: normal within this of vertical.")
	        .angle(
	            "ceiling_normal_tolerance_deg", &O::ceilingNormalTolerance, 0,
	            89, "Down-facing: normal within this of vertical.")
	        .angle(
	            "wall_normal_tolerance_deg", &O::wallNormalTolerance, 0, 89,
	            "Vertical: normal within this of horizontal.")
	        .angle(
	            "surface_join_angle_deg", &O::surfaceJoinAngle, 0, 180,
	            "Neighbours join a surface with normals this close...")
	        .angle(
	            "surface_max_angle_deg", &O::surfaceMaxAngle, 0, 180,
	            "...and this close to the surface's mean...")
	        .real(
	            "surface_max_range_step_m", &O::surfaceMaxRangeStep, 0, 100,
	            "...and ranges this close.")
	        .integer(
	            "min_surface_px", &O::minSurfacePixels, 1, 1000000,
	            "Smaller surfaces are left to the leftover step.")
	        .real(
	            "plane_merge_tolerance_m", &O::planeMergeTolerance, 0, 10,
	            "Coplanar vertical pieces of different areas are grouped...")
	        .angle(
	            "plane_merge_angle_deg", &O::planeMergeAngle, 0, 90,
	            "...with normals this close.")
	        .real(
	            "plane_split_offset_m", &O::planeSplitOffset, 0, 10,
	            "A group is split where its plane steps this much (a "
	            "recessed door).")
	        .real(
	            "wall_group_tolerance_m", &O::wallGroupTolerance, 0, 10,
	            "Pieces of one wall this close to its plane count together "
	            "for the size rules...")
	        .angle(
	            "wall_group_angle_deg", &O::wallGroupAngle, 0, 90,
	            "...with normals this close.")
	        .integer(
	            "plane_split_half_width_px", &O::planeSplitHalfWidth, 0, 20,
	            "Smoothing of the plane residuals before the split.")
	        .flag(
	            "auto_ground_level", &O::autoGroundLevel,
	            "Ground level from the up-facing pixels (else ground_z_m).")
	        .real(
	            "ground_z_m", &O::groundZ, -100, 100,
	            "Ground level (and the centre of the ground search).")
	        .real(
	            "ground_tolerance_m", &O::groundTolerance, 0, 10,
	            "Ground: up-facing, mean height this close to the ground "
	            "level.")
	        .real(
	            "ground_search_m", &O::groundSearch, 0, 100,
	            "On a robot, the ground is searched this close to "
	            "ground_z_m.")
	        .integer(
	            "min_ground_px", &O::minGroundPixels, 1, 1000000,
	            "Fewest up-facing pixels for a ground level.")
	        .real(
	            "ceiling_min_height_m", &O::ceilingMinHeight, 0, 100,
	            "Ceiling: down-facing, this high above the ground.")
	        .choice(
	            "environment", &O::environment,
	            {{O::Environment::Auto, "auto"},
	             {O::Environment::Indoor, "indoor"},
	             {O::Environment::Outdoor, "outdoor"}},
	            "auto (indoor when a ceiling is seen) | indoor | outdoor.")
	        .integer(
	            "indoor_min_ceiling_px", &O::indoorMinCeilingPixels, 1,
	            10000000, "auto: indoor when this many ceiling pixels.")
	        .real(
	            "wall_min_height_m", &O::wallMinHeight, 0, 100,
	            "Wall: vertical and this tall (from the ground when the field "
	            "of "
	            "view cuts its bottom)...")
	        .real(
	            "wall_ceiling_gap_m", &O::wallCeilingGap, 0, 100,
	            "...or reaching this close to the ceiling...")
	        .real(
	            "wall_min_length_m", &O::wallMinLength, 0, 1000,
	            "...or this long...")
	        .real(
	            "wall_long_min_reach_m", &O::wallLongMinReach, 0, 100,
	            "...and reaching this high above the ground (a low garden "
	            "wall is an obstacle).")
	        .real(
	            "wall_min_width_m", &O::wallMinWidth, 0, 100,
	            "Narrower vertical surfaces are a wall only when tall or "
	            "reaching the ceiling.")
	        .real(
	            "door_min_width_m", &O::doorMinWidth, 0, 100,
	            "Door: one vertical surface this wide...")
	        .real(
	            "door_max_width_m", &O::doorMaxWidth, 0, 100,
	            "...at most this wide...")
	        .real(
	            "door_framed_max_width_m", &O::doorFramedMaxWidth, 0, 100,
	            "...or up to this wide when wall is found on its left, right "
	            "and top (0 = off; a double door measured with its frame)...")
	        .real(
	            "door_min_height_m", &O::doorMinHeight, 0, 100,
	            "...this high...")
	        .real(
	            "door_max_height_m", &O::doorMaxHeight, 0, 100,
	            "...at most this high.")
	        .check(
	            [](const O& o)
	            {
		            return o.doorMinWidth <= o.doorMaxWidth &&
		                   o.doorMinHeight <= o.doorMaxHeight &&
		                   (o.doorFramedMaxWidth == 0 ||
		                    o.doorFramedMaxWidth >= o.doorMaxWidth);
	            },
	            "door minimum width/height above the maximum, or "
	            "door_framed_max_width_m under door_max_width_m")
	        .real(
	            "door_bottom_tolerance_m", &O::doorBottomTolerance, 0, 10,
	            "A door's bottom is this close to the ground.")
	        .real(
	            "door_max_offset_m", &O::doorMaxOffset, 0, 10,
	            "Walls left, right and on top within this of its plane...")
	        .angle(
	            "door_max_angle_deg", &O::doorMaxAngle, 0, 90,
	            "...and parallel within this...")
	        .real(
	            "door_min_offset_m", &O::doorMinOffset, 0, 10,
	            "...and it stands off them by this.")
	        .real(
	            "door_framed_min_offset_m", &O::doorFramedMinOffset, 0, 10,
	            "A door framed all round (door_framed_side_fraction) needs to "
	            "stand off its walls by this only.")
	        .real(
	            "door_framed_side_fraction", &O::doorFramedSideFraction, 0, 1,
	            "Framed all round: wall along this share of its left, right "
	            "and top, none cut by the field of view.")
	        .flag(
	            "door_allow_truncation", &O::doorAllowTruncation,
	            "A side cut by the field of view stands in for a wall.")
	        .integer(
	            "door_search_px", &O::doorSearchPixels, 1, 1000,
	            "The walls around a door are searched this far...")
	        .real(
	            "door_search_m", &O::doorSearchDistance, 0, 10,
	            "...or this far (at the door's pixel spacing), if farther,")
	        .real(
	            "door_search_min_size_m", &O::doorSearchMinSize, 0, 10,
	            "...around a door that shows this much of its width and "
	            "height.")
	        .real(
	            "door_seam_split_offset_m", &O::doorSeamSplitOffset, 0, 10,
	            "A smaller plane step (a nearly flush door) splits between "
	            "vertical seams...")
	        .real(
	            "door_seam_depth_m", &O::doorSeamDepth, 0, 10,
	            "...lines of pixels this far off the plane (a gap, a "
	            "frame)...")
	        .real(
	            "door_seam_min_height_m", &O::doorSeamMinHeight, 0, 10,
	            "...this tall...")
	        .integer(
	            "door_seam_min_notches", &O::doorSeamMinNotches, 1, 100000,
	            "...seen in this many rows; or where that share of its "
	            "boundary is such a seam:")
	        .real(
	            "door_seam_min_share", &O::doorSeamMinShare, 0, 1,
	            "(the share)")
	        .real(
	            "door_min_side_fraction", &O::doorMinSideFraction, 0, 1,
	            "A side is a wall when this share of it is...")
	        .real(
	            "door_single_side_fraction", &O::doorSingleSideFraction, 0, 1,
	            "...and this share when it is the only wall side (the others "
	            "cut by the field of view).")
	        .flag(
	            "door_lintel_one_side", &O::doorLintelOneSide,
	            "A leaf with walls above it (a lintel) and on one side is a "
	            "door (the other side hidden by a reveal, a corner or a far "
	            "wall).")
	        .real(
	            "door_occlusion_margin_m", &O::doorOcclusionMargin, 0, 10,
	            "A side of a leaf whose neighbours are nearer to the sensor by "
	            "this is hidden: its width or bottom there is a lower bound "
	            "(0: off).")
	        .flag(
	            "door_shape_split", &O::doorShapeSplit,
	            "A plane step of door_seam_split_offset_m without seams splits "
	            "when one side is a leaf-shaped box under the other.")
	        .flag(
	            "door_lintel_split", &O::doorLintelSplit,
	            "A stretch of a wall door_search_min_size_m to "
	            "door_max_width_m wide whose lower part steps by "
	            "door_seam_split_offset_m from the wall above it (a leaf under "
	            "its lintel), while the wall beside it does not, splits off.")
	        .flag(
	            "door_lintel_after_cut", &O::doorLintelAfterCut,
	            "After a group is cut at a plane step (plane_split_offset_m, "
	            "or between seams), each side is searched again for a leaf "
	            "under its lintel (door_lintel_split).")
	        .flag(
	            "door_lintel_3d", &O::doorLintel3d,
	            "A leaf cut by the field of view at its top or a side is a "
	            "door "
	            "when walls of its plane lie above it (in 3D, wherever the "
	            "image puts them) along door_min_side_fraction of its width.")
	        .real(
	            "door_recessed_leaf_offset_m", &O::doorRecessedLeafOffset, 0,
	            10,
	            "A leaf cut by the field of view at its top, bottom and one "
	            "side is a door when it stands off the walls of its plane "
	            "found beside its other side by this (recessed; 0: off)...")
	        .real(
	            "door_recessed_leaf_side_fraction",
	            &O::doorRecessedLeafSideFraction, 0, 1,
	            "...found along this share of that side.")
	        .real(
	            "door_recessed_frame_side_fraction",
	            &O::doorRecessedFrameSideFraction, 0, 1,
	            "A leaf standing off its walls by door_recessed_leaf_offset_m, "
	            "its left, right and top not cut by the field of view, is a "
	            "door with walls along this share of each (0: off).")
	        .real(
	            "door_framed_min_width_m", &O::doorFramedMinWidth, 0, 10,
	            "A candidate narrower than door_min_width_m but this wide, cut "
	            "by the field of view at its bottom, is a door with walls "
	            "along "
	            "door_single_side_fraction of its left, right and top, none "
	            "cut by the field of view (0: off).")
	        .real(
	            "sidewalk_min_rbar", &O::sidewalkMinRbar, -1, 1,
	            "Outdoor ground: sidewalk where R-bar is at least this, "
	            "else grass.")
	        .real(
	            "sidewalk_max_height_std_m", &O::sidewalkMaxHeightStd, 0, 10,
	            "Squares without R-bar: sidewalk when their heights spread "
	            "at most this.")
	        .integer(
	            "min_patch_squares", &O::minPatchSquares, 0, 1000000,
	            "Smaller sidewalk/grass patches are absorbed.")
	        .integer(
	            "sidewalk_border_half_width_px", &O::sidewalkBorderHalfWidth, 0,
	            20,
	            "Squares on the sidewalk/grass border: each pixel by the "
	            "mean R of the (2h+1)^2 window centred on it (0: off).")
	        .real(
	            "sidewalk_flat_max_height_std_m", &O::sidewalkFlatMaxHeightStd,
	            0, 10,
	            "Squares grass by R-bar: sidewalk when their heights spread "
	            "at most this (0: off).")
	        .real(
	            "leftover_plane_tolerance_m", &O::leftoverPlaneTolerance, 0, 10,
	            "Pixels left over join a neighbouring surface this close to "
	            "its plane.")
	        .flag(
	            "classify_leftover_pixels", &O::classifyLeftoverPixels,
	            "Label the pixels left over (for pixel-level scoring).")
	        .real(
	            "wall_plane_reclaim_m", &O::wallPlaneReclaimTolerance, 0, 1,
	            "Pixels labelled obstacle, 4-connected to a wall through "
	            "pixels this close to that wall's plane, become wall (0: "
	            "off).")
	        .flag(
	            "wall_plane_reclaim_ceilings", &O::wallPlaneReclaimCeilings,
	            "wall_plane_reclaim_m: ceiling surfaces reclaim the "
	            "obstacle pixels on their planes too.");
	return t;
}
}  // namespace

SEMNAV_OPTIONS_FROM_TABLE(RuleClassifier::TOptions, optionTable())

}  // namespace semnav
