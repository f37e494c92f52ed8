/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/config/CConfigFile.h>
#include <mrpt/config/CConfigFileBase.h>
#include <semnav/cascade/CascadeError.h>
#include <semnav/cascade/CascadeEvaluator.h>
#include <semnav/cascade/CascadeXml.h>
#include <semnav/cascade/ExactResize.h>
#include <semnav/cascade/IntegralImages.h>
#include <semnav/cascade/RangeGate.h>
#include <semnav/common/ClassRegistry.h>
#include <semnav/common/Error.h>
#include <semnav/common/OptionTable.h>
#include <semnav/common/ParallelFor.h>
#include <semnav/common/Percentile.h>
#include <semnav/common/Timing.h>
#include <semnav/detection/BackWall.h>
#include <semnav/detection/CascadeDetector.h>
#include <semnav/detection/ShapeVerifier.h>

#include <algorithm>
#include <chrono>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <opencv2/imgproc.hpp>
#include <opencv2/objdetect.hpp>
#include <sstream>
#include <tuple>

namespace semnav
{
namespace
{
using Clock = std::chrono::steady_clock;

using C = CascadeDetector::TClassOptions;
const OptionTable<C>& classTable()
{
	static const auto t =
	    OptionTable<C>()
	        .text(
	            "cascade", &C::cascade,
	            "Cascade XML (relative to this file's directory).")
	        .check(
	            [](const C& o) { return !o.cascade.empty(); },
	            "cascade must name a cascade XML file")
	        .real(
	            "upscale", &C::upscale, 0.25, 8.0,
	            "Near pass: the detection image is scaled by this.")
	        .angle(
	            "min_elevation_deg", &C::minElevation, -90, 90,
	            "Near pass: lowest elevation searched.")
	        .angle(
	            "max_elevation_deg", &C::maxElevation, -90, 90,
	            "Near pass: highest elevation searched.")
	        .real(
	            "far_upscale", &C::farUpscale, 0, 8.0,
	            "Far pass scale (0: no far pass).")
	        .real(
	            "far_below_px", &C::farBelowPx, 0, 10000,
	            "Objects smaller than this (box side) are left to the far "
	            "pass.")
	        .angle(
	            "far_min_elevation_deg", &C::farMinElevation, -90, 90,
	            "Far pass: lowest elevation searched.")
	        .angle(
	            "far_max_elevation_deg", &C::farMaxElevation, -90, 90,
	            "Far pass: highest elevation searched.")
	        .real(
	            "scale_factor", &C::scaleFactor, 1.01, 3.0,
	            "detectMultiScale's scale factor.")
	        .integer(
	            "min_neighbors", &C::minNeighbors, 0, 100,
	            "detectMultiScale's min_neighbors.")
	        .integer(
	            "window_step", &C::windowStep, 0, 8,
	            "Step between windows with range_scales (0: "
	            "detectMultiScale's).")
	        .real(
	            "max_size_px", &C::maxSizePx, 0, 10000,
	            "Largest box side searched (0: the image).")
	        .real(
	            "min_width_m", &C::minWidth, 0, 100,
	            "Object width across the line of sight: at least...")
	        .real("max_width_m", &C::maxWidth, 0, 100, "...at most.")
	        .real(
	            "min_top_m", &C::minTop, -10, 100,
	            "Height of the object's top above the ground: at least...")
	        .real("max_top_m", &C::maxTop, -10, 100, "...at most.")
	        .real(
	            "max_depth_m", &C::maxDepth, 0.01, 100,
	            "Object points lie at most this far behind its nearest "
	            "part.")
	        .integer(
	            "min_points", &C::minPoints, 1, 1000000,
	            "Fewer object points: rejected.")
	        .real(
	            "min_size_m", &C::minSize, 0.01, 100,
	            "Larger side of a whole object: at least...")
	        .real(
	            "min_cut_size_m", &C::minCutSize, 0.01, 100,
	            "...(of one whose foot is not seen)...")
	        .real("max_size_m", &C::maxSize, 0.01, 100, "...at most.")
	        .integer(
	            "proposal_min_neighbors", &C::proposalMinNeighbors, -1, 100,
	            "min_neighbors around proposals (-1: min_neighbors).")
	        .real(
	            "border_px", &C::borderPx, 0, 1000,
	            "Zero padding of each pass's band (windows around objects "
	            "cut by the edge).")
	        .optional(
	            "channel",
	            [](C& o, const mrpt::config::CConfigFileBase& c,
	               const std::string& s)
	            {
		            if (!c.keyExists(s, "channel")) return;
		            try
		            {
			            o.channel = channelFromName(
			                c.read_string(s, "channel", "", true));
		            }
		            catch (const ConfigError& e)
		            {
			            throw ConfigError("[" + s + "] channel: " + e.what());
		            }
	            },
	            [](const C& o, std::string& out)
	            {
		            if (o.channel) out = channelName(*o.channel);
		            return o.channel.has_value();
	            },
	            "This class's detection image (unset: [CascadeDetector]'s).")
	        .text(
	            "shape_model", &C::shapeModel,
	            "ShapeVerifier forest (relative as cascade); empty: no "
	            "shape check.")
	        .real(
	            "min_shape_score", &C::minShapeScore, 0, 1,
	            "Detections the forest scores lower are rejected.")
	        .angle(
	            "side_bearing_deg", &C::sideBearing, 0, 90,
	            "Detections at this bearing or more are beside the robot (90: "
	            "none).")
	        .real(
	            "side_min_shape_score", &C::sideMinShapeScore, 0, 1,
	            "Beside the robot the forest must score at least this too (0: "
	            "min_shape_score only).")
	        .integer(
	            "max_stages", &C::maxStages, 0, 1000,
	            "Only the first this many stages are evaluated (0: all).")
	        .flag(
	            "segment_candidates", &C::segmentCandidates,
	            "Every 3D segment of the object points is also a candidate.")
	        .flag(
	            "cascade_support", &C::cascadeSupport,
	            "The shape model sees how many cascade windows cover a "
	            "candidate.")
	        .real(
	            "back_wall_length_m", &C::backWallLength, 0, 100,
	            "A wall this long behind the object is cut off (0: none).")
	        .real(
	            "max_continuing_share", &C::maxContinuingShare, 0, 1,
	            "Rejected when more columns continue upwards (1: no check).")
	        .real(
	            "max_overhead_share", &C::maxOverheadShare, 0, 1,
	            "Rejected when more columns have something over the object, "
	            "e.g. a pot's foliage (1: no check).")
	        .real(
	            "min_flat_face_share", &C::minFlatFaceShare, 0, 1,
	            "Rejected when less of the top's front runs along one box's "
	            "faces, e.g. a plant's round foliage (0: no check).")
	        .real(
	            "min_separation_m", &C::minSeparation, 0, 100,
	            "Detections closer than this are one object (0: no check).")
	        .real(
	            "grow_m", &C::grow, 0, 10,
	            "An accepted object is measured again in its box grown by "
	            "this (0: not).")
	        .check(
	            [](const C& o)
	            {
		            return !(
		                o.minWidth > o.maxWidth || o.minTop > o.maxTop ||
		                o.minSize > o.maxSize || o.minCutSize > o.maxSize ||
		                o.minElevation >= o.maxElevation ||
		                (o.farUpscale > 0 &&
		                 o.farMinElevation >= o.farMaxElevation));
	            },
	            "a minimum exceeds its maximum");
	return t;
}

using O = CascadeDetector::TOptions;

/** `classes` and their sections [<section>.<label>]. */
void loadClasses(
    O& o, const mrpt::config::CConfigFileBase& c, const std::string& s)
{
	std::string list;
	for (const auto& k : o.classes) list += labelName(k.label) + " ";
	list = c.read_string(s, "classes", list, false);
	std::istringstream in(list);
	std::vector<CascadeDetector::TClassOptions> loaded;
	for (std::string name; in >> name;)
	{
		Label l;
		try
		{
			l = labelFromName(name);
		}
		catch (const Error& e)
		{
			throw ConfigError("[" + s + "] classes: " + e.what());
		}
		for (const auto& k : loaded)
			if (k.label == l)
				throw ConfigError(
				    "[" + s + "] classes lists " + name + " twice");
		CascadeDetector::TClassOptions k(l);
		for (const auto& d : o.classes)
			if (d.label == l) k = d;  // defaults of a known class
		k.loadFromConfigFile(c, s + "." + name);
		loaded.push_back(k);
	}
	o.classes = loaded;
}

const OptionTable<O>& optionTable()
{
	static const auto t =
	    OptionTable<O>()
	        .named(
	            "channel", &O::channel, channelFromName, channelName,
	            "Image the cascades see: grey | red | green | blue | view.")
	        .integer(
	            "normal_smoothing_px", &O::normalSmoothing, 0, 10,
	            "Half width of the normal averaging before the image is "
	            "made.")
	        .choice(
	            "projection", &O::panoramic,
	            {{true, "panoramic"}, {false, "sweep"}},
	            "panoramic (azimuth x elevation) | sweep (rows and "
	            "columns, as the paper).")
	        .custom(
	            "classes", loadClasses,
	            [](const O& o)
	            {
		            std::string list;
		            for (const auto& k : o.classes)
			            list += (list.empty() ? "" : " ") + labelName(k.label);
		            return list;
	            },
	            "Classes with a cascade; each has a section "
	            "[CascadeDetector.<label>].")
	        .flag(
	            "label_pixels", &O::labelPixels,
	            "Object pixels of a detection get its label.")
	        .real(
	            "floor_tolerance_m", &O::floorTolerance, 0, 1,
	            "Points this close to the ground are floor, not object.")
	        .real(
	            "measure_margin", &O::measureMargin, 0, 2,
	            "An object is measured in its box grown by this share of "
	            "its side.")
	        .flag(
	            "connected_object", &O::connectedObject,
	            "The object is the points connected to the box centre's.")
	        .flag(
	            "proposals", &O::proposals,
	            "Search only windows around the regions the rules left to "
	            "objects.")
	        .integer(
	            "proposal_min_pixels", &O::proposalMinPixels, 1, 1000000,
	            "Smaller regions are dropped.")
	        .integer(
	            "proposal_join_px", &O::proposalJoinPx, 0, 20,
	            "Object pixels this close join one region...")
	        .real(
	            "proposal_max_height_m", &O::proposalMaxHeight, 0.05, 20,
	            "Object points higher than this are not proposals.")
	        .real(
	            "proposal_margin", &O::proposalMargin, 0, 5,
	            "The search window is the region grown by this share of "
	            "the window side.")
	        .real(
	            "proposal_size_slack", &O::proposalSizeSlack, 1, 10,
	            "Expected window sides are widened by this both ways.")
	        .real(
	            "proposal_foot_height_m", &O::proposalFootHeight, 0, 5,
	            "A region this close to the ground shows its object whole.")
	        .real(
	            "proposal_fill", &O::proposalFill, 0, 1,
	            "An object fills at least this share of its region's "
	            "larger side.")
	        .real(
	            "proposal_range_gap_m", &O::proposalRangeGap, 0, 100,
	            "Pixels of one region differ in range by at most this (+ 5 %).")
	        .real(
	            "proposal_top_margin_m", &O::proposalTopMargin, 0, 10,
	            "Regions hold points at most max_top_m + this high.")
	        .flag(
	            "proposal_size_check", &O::proposalSizeCheck,
	            "Skip regions whose real size cannot hold the class.")
	        .flag(
	            "range_scales", &O::rangeScales,
	            "Evaluate only windows whose size fits the class at their "
	            "range.")
	        .real(
	            "range_scale_slack", &O::rangeScaleSlack, 1, 10,
	            "The range gate's sizes widened by this both ways.")
	        .real(
	            "range_cut_m", &O::rangeCut, 0, 100,
	            "Closer, the lowest tilt line cuts objects (min_cut_size_m).")
	        .flag(
	            "range_objects_only", &O::rangeObjectsOnly,
	            "Windows only around the points the rules left to objects.")
	        .real(
	            "segment_range_gap_m", &O::segmentRangeGap, 0, 100,
	            "Segments (segment_candidates) split at range gaps this "
	            "large.")
	        .real(
	            "segment_max_taller", &O::segmentMaxTaller, 0, 1e6,
	            "A segment joined by more higher object pixels than this "
	            "share is no candidate.")
	        .flag(
	            "segment_range_window", &O::segmentRangeWindow,
	            "A segment is measured over its own horizontal range only.")
	        .integer(
	            "threads", &O::threads, 0, 64,
	            "Threads over classes, passes and candidates; 0 = all "
	            "cores.");
	return t;
}
}  // namespace

// ------------------------------------------------------------ options
CascadeDetector::TClassOptions::TClassOptions() = default;
CascadeDetector::TClassOptions::TClassOptions(Label l) : label(l)
{
	// The class's row in the registry: its files and plausible sizes.
	const ClassInfo& info = classInfo(l);
	cascade = info.cascadeFile.empty() ? info.name + ".xml" : info.cascadeFile;
	const auto& p = info.plausibility;
	if (p.maxWidth < ClassInfo::kInf)
	{
		minWidth = p.minWidth;
		maxWidth = p.maxWidth;
	}
	if (p.maxTop < ClassInfo::kInf)
	{
		minTop = p.minTop;
		maxTop = p.maxTop;
	}
	if (p.maxDepth < ClassInfo::kInf) maxDepth = p.maxDepth;
}

const std::vector<std::string>& CascadeDetector::TClassOptions::knownKeys()
{
	static const std::vector<std::string> keys = classTable().keys();
	return keys;
}

SEMNAV_OPTIONS_FROM_TABLE(CascadeDetector::TClassOptions, classTable())

std::vector<DetectionPass> CascadeDetector::TClassOptions::passes(
    int rows, double el0, double el1, cv::Size window) const
{
	const auto row = [&](double el)
	{
		if (rows < 2 || el1 <= el0) return el < el0 ? 0 : rows;
		const double v = (el - el0) / (el1 - el0) * (rows - 1);
		return std::clamp(static_cast<int>(std::lround(v)), 0, rows);
	};
	const double win = std::max(window.width, window.height);
	std::vector<DetectionPass> out;
	DetectionPass nearPass;
	nearPass.upscale = upscale;
	nearPass.rowBegin = row(minElevation);
	nearPass.rowEnd = std::max(nearPass.rowBegin, row(maxElevation) + 1);
	nearPass.minSide = win / upscale;
	nearPass.maxSide = maxSizePx;
	if (farUpscale > 0 && farBelowPx > 0)
	{
		DetectionPass farPass;
		farPass.upscale = farUpscale;
		farPass.rowBegin = row(farMinElevation);
		farPass.rowEnd = std::max(farPass.rowBegin, row(farMaxElevation) + 1);
		farPass.minSide = win / farUpscale;
		farPass.maxSide = std::max(farBelowPx, farPass.minSide);
		nearPass.minSide = std::max(nearPass.minSide, farBelowPx);
		out.push_back(farPass);
	}
	out.insert(out.begin(), nearPass);
	return out;
}

CascadeDetector::TOptions::TOptions()
{
	// Built-in defaults for the paper's three classes: sizes and files from
	// the class registry, the search passes here (config/cascade.ini holds
	// the tuned values).
	TClassOptions wb(Label::Washbasin);
	wb.upscale = 1.0;
	wb.farUpscale = 2.5;
	wb.farBelowPx = 24;
	wb.minSize = 0.7;
	wb.minCutSize = 0.35;
	wb.maxSize = 1.2;
	TClassOptions bin(Label::Wastebasket);
	bin.upscale = 1.0;
	bin.farUpscale = 3.0;
	bin.farBelowPx = 24;
	bin.minSize = 0.28;
	bin.minCutSize = 0.2;
	bin.maxSize = 0.6;
	TClassOptions st(Label::Stairs);
	st.upscale = 1.0;
	st.minSize = 0.8;
	st.minCutSize = 0.6;
	st.maxSize = 3.0;
	classes = {wb, bin, st};
}

const std::vector<std::string>& CascadeDetector::TOptions::knownKeys()
{
	static const std::vector<std::string> keys = optionTable().keys();
	return keys;
}

void CascadeDetector::TOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& c, const std::string& s)
{
	optionTable().load(*this, c, s);
}

void CascadeDetector::TOptions::saveToConfigFile(
    mrpt::config::CConfigFileBase& c, const std::string& s) const
{
	optionTable().save(*this, c, s);
	for (const auto& k : classes)
		k.saveToConfigFile(c, s + "." + labelName(k.label));
}

CascadeDetector::TOptions CascadeDetector::TOptions::fromIniFile(
    const std::string& path, const std::string& section)
{
	std::vector<std::string> sections{
	    section, "SampleGenerator", "CascadeTrainer", "NormalImage"};
	for (Label l : allLabels())
	{
		sections.push_back(section + "." + labelName(l));
		sections.push_back("CascadeTrainer." + labelName(l));
		sections.push_back("SampleGenerator." + labelName(l));
	}
	const auto cfg = openIniFile(path, sections);
	TOptions o;
	o.loadFromConfigFile(*cfg, section);
	const auto dir = std::filesystem::path(path).parent_path();
	o.baseDir = dir.empty() ? "." : dir.string();
	return o;
}

RangeGate CascadeDetector::TOptions::rangeGate(
    const TClassOptions& c, double step, double upscale) const
{
	RangeGate g;
	// The training window is the object's larger side + 15 %.
	g.perSide = 1.15 * upscale / step;
	g.lo = c.minSize / rangeScaleSlack;
	g.loCut = c.minCutSize / rangeScaleSlack;
	g.hi = c.maxSize * rangeScaleSlack;
	g.cutRange = rangeCut;
	return g;
}

const CascadeDetector::TClassOptions& CascadeDetector::TOptions::classOptions(
    Label l) const
{
	for (const auto& k : classes)
		if (k.label == l) return k;
	throw ConfigError("no cascade is configured for " + labelName(l));
}

ObjectProposals::Params CascadeDetector::TOptions::proposalParams(
    int joinRadius, double rangeGap) const
{
	ObjectProposals::Params pp;
	pp.floorTolerance = floorTolerance;
	pp.maxHeight = proposalMaxHeight;
	pp.minPixels = proposalMinPixels;
	pp.joinRadius = joinRadius;
	pp.rangeGap = rangeGap;
	return pp;
}

std::string CascadeDetector::TOptions::cascadePath(const TClassOptions& c) const
{
	return resolvePath(c.cascade);
}

std::string CascadeDetector::TOptions::resolvePath(
    const std::string& file) const
{
	const std::filesystem::path p(file);
	if (p.is_absolute()) return p.string();
	return (std::filesystem::path(baseDir) / p).lexically_normal().string();
}
}  // namespace semnav
