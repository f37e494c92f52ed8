/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/core/bits_math.h>
#include <semnav/common/ConfigChecks.h>
#include <semnav/common/Error.h>
#include <semnav/perception/RuleClassifier.h>

#include <string>

namespace semnav
{
using mrpt::DEG2RAD;
using mrpt::RAD2DEG;

namespace
{
const char* envName(RuleClassifier::TOptions::Environment e)
{
	switch (e)
	{
		case RuleClassifier::TOptions::Environment::Indoor:
			return "indoor";
		case RuleClassifier::TOptions::Environment::Outdoor:
			return "outdoor";
		default:
			return "auto";
	}
}
}  // namespace

void RuleClassifier::TOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& c, const std::string& s)
{
	checkKnownKeys(
	    c, s,
	    {"normal_smoothing_half_width_px",
	     "ground_normal_tolerance_deg",
	     "ceiling_normal_tolerance_deg",
	     "wall_normal_tolerance_deg",
	     "surface_join_angle_deg",
	     "surface_max_angle_deg",
	     "surface_max_range_step_m",
	     "min_surface_px",
	     "plane_merge_tolerance_m",
	     "plane_merge_angle_deg",
	     "plane_split_offset_m",
	     "wall_group_tolerance_m",
	     "wall_group_angle_deg",
	     "plane_split_half_width_px",
	     "auto_ground_level",
	     "ground_z_m",
	     "ground_tolerance_m",
	     "ground_search_m",
	     "min_ground_px",
	     "ceiling_min_height_m",
	     "environment",
	     "indoor_min_ceiling_px",
	     "wall_min_height_m",
	     "wall_ceiling_gap_m",
	     "wall_min_length_m",
	     "wall_min_width_m",
	     "door_min_width_m",
	     "door_max_width_m",
	     "door_min_height_m",
	     "door_max_height_m",
	     "door_bottom_tolerance_m",
	     "door_max_offset_m",
	     "door_max_angle_deg",
	     "door_min_offset_m",
	     "door_allow_truncation",
	     "door_search_px",
	     "door_min_side_fraction",
	     "sidewalk_min_rbar",
	     "sidewalk_max_height_std_m",
	     "min_patch_squares",
	     "leftover_plane_tolerance_m",
	     "classify_leftover_pixels"});
	auto deg = [&](const char* key, double& v, double lo, double hi)
	{ v = DEG2RAD(readChecked(c, s, key, RAD2DEG(v), lo, hi)); };
	normalSmoothingHalfWidth = readCheckedInt(
	    c, s, "normal_smoothing_half_width_px", normalSmoothingHalfWidth, 0,
	    10);
	deg("ground_normal_tolerance_deg", groundNormalTolerance, 0, 89);
	deg("ceiling_normal_tolerance_deg", ceilingNormalTolerance, 0, 89);
	deg("wall_normal_tolerance_deg", wallNormalTolerance, 0, 89);
	deg("surface_join_angle_deg", surfaceJoinAngle, 0, 180);
	deg("surface_max_angle_deg", surfaceMaxAngle, 0, 180);
	surfaceMaxRangeStep = readChecked(
	    c, s, "surface_max_range_step_m", surfaceMaxRangeStep, 0, 100);
	minSurfacePixels =
	    readCheckedInt(c, s, "min_surface_px", minSurfacePixels, 1, 1000000);
	planeMergeTolerance = readChecked(
	    c, s, "plane_merge_tolerance_m", planeMergeTolerance, 0, 10);
	deg("plane_merge_angle_deg", planeMergeAngle, 0, 90);
	planeSplitOffset =
	    readChecked(c, s, "plane_split_offset_m", planeSplitOffset, 0, 10);
	wallGroupTolerance =
	    readChecked(c, s, "wall_group_tolerance_m", wallGroupTolerance, 0, 10);
	deg("wall_group_angle_deg", wallGroupAngle, 0, 90);
	planeSplitHalfWidth = readCheckedInt(
	    c, s, "plane_split_half_width_px", planeSplitHalfWidth, 0, 20);
	autoGroundLevel =
	    readCheckedBool(c, s, "auto_ground_level", autoGroundLevel);
	groundZ = readChecked(c, s, "ground_z_m", groundZ, -100, 100);
	groundTolerance =
	    readChecked(c, s, "ground_tolerance_m", groundTolerance, 0, 10);
	groundSearch = readChecked(c, s, "ground_search_m", groundSearch, 0, 100);
	minGroundPixels =
	    readCheckedInt(c, s, "min_ground_px", minGroundPixels, 1, 1000000);
	ceilingMinHeight =
	    readChecked(c, s, "ceiling_min_height_m", ceilingMinHeight, 0, 100);
	const std::string env =
	    c.read_string(s, "environment", envName(environment));
	if (env == "auto")
		environment = Environment::Auto;
	else if (env == "indoor")
		environment = Environment::Indoor;
	else if (env == "outdoor")
		environment = Environment::Outdoor;
	else
		throw ConfigError(
		    "[" + s + "] environment = '" + env +
		    "' is not one of auto, indoor, outdoor");
	indoorMinCeilingPixels = readCheckedInt(
	    c, s, "indoor_min_ceiling_px", indoorMinCeilingPixels, 1, 10000000);
	wallMinHeight =
	    readChecked(c, s, "wall_min_height_m", wallMinHeight, 0, 100);
	wallCeilingGap =
	    readChecked(c, s, "wall_ceiling_gap_m", wallCeilingGap, 0, 100);
	wallMinLength =
	    readChecked(c, s, "wall_min_length_m", wallMinLength, 0, 1000);
	wallMinWidth = readChecked(c, s, "wall_min_width_m", wallMinWidth, 0, 100);
	doorMinWidth = readChecked(c, s, "door_min_width_m", doorMinWidth, 0, 100);
	doorMaxWidth = readChecked(c, s, "door_max_width_m", doorMaxWidth, 0, 100);
	doorMinHeight =
	    readChecked(c, s, "door_min_height_m", doorMinHeight, 0, 100);
	doorMaxHeight =
	    readChecked(c, s, "door_max_height_m", doorMaxHeight, 0, 100);
	if (doorMinWidth > doorMaxWidth || doorMinHeight > doorMaxHeight)
		throw ConfigError(
		    "[" + s + "] door minimum width/height above the maximum");
	doorBottomTolerance = readChecked(
	    c, s, "door_bottom_tolerance_m", doorBottomTolerance, 0, 10);
	doorMaxOffset =
	    readChecked(c, s, "door_max_offset_m", doorMaxOffset, 0, 10);
	deg("door_max_angle_deg", doorMaxAngle, 0, 90);
	doorMinOffset =
	    readChecked(c, s, "door_min_offset_m", doorMinOffset, 0, 10);
	doorAllowTruncation =
	    readCheckedBool(c, s, "door_allow_truncation", doorAllowTruncation);
	doorSearchPixels =
	    readCheckedInt(c, s, "door_search_px", doorSearchPixels, 1, 1000);
	doorMinSideFraction =
	    readChecked(c, s, "door_min_side_fraction", doorMinSideFraction, 0, 1);
	sidewalkMinRbar =
	    readChecked(c, s, "sidewalk_min_rbar", sidewalkMinRbar, -1, 1);
	sidewalkMaxHeightStd = readChecked(
	    c, s, "sidewalk_max_height_std_m", sidewalkMaxHeightStd, 0, 10);
	minPatchSquares =
	    readCheckedInt(c, s, "min_patch_squares", minPatchSquares, 0, 1000000);
	leftoverPlaneTolerance = readChecked(
	    c, s, "leftover_plane_tolerance_m", leftoverPlaneTolerance, 0, 10);
	classifyLeftoverPixels = readCheckedBool(
	    c, s, "classify_leftover_pixels", classifyLeftoverPixels);
}

void RuleClassifier::TOptions::saveToConfigFile(
    mrpt::config::CConfigFileBase& c, const std::string& s) const
{
	c.write(s, "normal_smoothing_half_width_px", normalSmoothingHalfWidth);
	c.write(s, "ground_normal_tolerance_deg", RAD2DEG(groundNormalTolerance));
	c.write(s, "ceiling_normal_tolerance_deg", RAD2DEG(ceilingNormalTolerance));
	c.write(s, "wall_normal_tolerance_deg", RAD2DEG(wallNormalTolerance));
	c.write(s, "surface_join_angle_deg", RAD2DEG(surfaceJoinAngle));
	c.write(s, "surface_max_angle_deg", RAD2DEG(surfaceMaxAngle));
	c.write(s, "surface_max_range_step_m", surfaceMaxRangeStep);
	c.write(s, "min_surface_px", minSurfacePixels);
	c.write(s, "plane_merge_tolerance_m", planeMergeTolerance);
	c.write(s, "plane_merge_angle_deg", RAD2DEG(planeMergeAngle));
	c.write(s, "plane_split_offset_m", planeSplitOffset);
	c.write(s, "wall_group_tolerance_m", wallGroupTolerance);
	c.write(s, "wall_group_angle_deg", RAD2DEG(wallGroupAngle));
	c.write(s, "plane_split_half_width_px", planeSplitHalfWidth);
	writeBool(c, s, "auto_ground_level", autoGroundLevel);
	c.write(s, "ground_z_m", groundZ);
	c.write(s, "ground_tolerance_m", groundTolerance);
	c.write(s, "ground_search_m", groundSearch);
	c.write(s, "min_ground_px", minGroundPixels);
	c.write(s, "ceiling_min_height_m", ceilingMinHeight);
	c.write(s, "environment", std::string(envName(environment)));
	c.write(s, "indoor_min_ceiling_px", indoorMinCeilingPixels);
	c.write(s, "wall_min_height_m", wallMinHeight);
	c.write(s, "wall_ceiling_gap_m", wallCeilingGap);
	c.write(s, "wall_min_length_m", wallMinLength);
	c.write(s, "wall_min_width_m", wallMinWidth);
	c.write(s, "door_min_width_m", doorMinWidth);
	c.write(s, "door_max_width_m", doorMaxWidth);
	c.write(s, "door_min_height_m", doorMinHeight);
	c.write(s, "door_max_height_m", doorMaxHeight);
	c.write(s, "door_bottom_tolerance_m", doorBottomTolerance);
	c.write(s, "door_max_offset_m", doorMaxOffset);
	c.write(s, "door_max_angle_deg", RAD2DEG(doorMaxAngle));
	c.write(s, "door_min_offset_m", doorMinOffset);
	writeBool(c, s, "door_allow_truncation", doorAllowTruncation);
	c.write(s, "door_search_px", doorSearchPixels);
	c.write(s, "door_min_side_fraction", doorMinSideFraction);
	c.write(s, "sidewalk_min_rbar", sidewalkMinRbar);
	c.write(s, "sidewalk_max_height_std_m", sidewalkMaxHeightStd);
	c.write(s, "min_patch_squares", minPatchSquares);
	c.write(s, "leftover_plane_tolerance_m", leftoverPlaneTolerance);
	writeBool(c, s, "classify_leftover_pixels", classifyLeftoverPixels);
}

}  // namespace semnav
