/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/config/CConfigFile.h>
#include <mrpt/config/CConfigFileBase.h>
#include <semnav/cascade/CascadeError.h>
#include <semnav/cascade/CascadeEvaluator.h>
#include <semnav/cascade/CascadeXml.h>
#include <semnav/cascade/ExactResize.h>
#include <semnav/cascade/IntegralImages.h>
#include <semnav/cascade/RangeGate.h>
#include <semnav/common/ConfigChecks.h>
#include <semnav/common/Error.h>
#include <semnav/common/ParallelFor.h>
#include <semnav/common/Percentile.h>
#include <semnav/common/Timing.h>
#include <semnav/detection/BackWall.h>
#include <semnav/detection/CascadeDetector.h>
#include <semnav/detection/ObjectScorer.h>
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
std::string num(double v)
{
	char buf[64];
	std::snprintf(buf, sizeof(buf), "%.12g", v);
	return buf;
}

using Clock = std::chrono::steady_clock;
}  // namespace

// ------------------------------------------------------------ options
CascadeDetector::TClassOptions::TClassOptions() = default;
CascadeDetector::TClassOptions::TClassOptions(Label l) : label(l)
{
	cascade = labelName(l) + ".xml";
}

const std::vector<std::string>& CascadeDetector::TClassOptions::knownKeys()
{
	static const std::vector<std::string> keys{
	    "cascade",
	    "upscale",
	    "min_elevation_deg",
	    "max_elevation_deg",
	    "far_upscale",
	    "far_below_px",
	    "far_min_elevation_deg",
	    "far_max_elevation_deg",
	    "scale_factor",
	    "min_neighbors",
	    "window_step",
	    "max_size_px",
	    "min_width_m",
	    "max_width_m",
	    "min_top_m",
	    "max_top_m",
	    "max_depth_m",
	    "min_points",
	    "min_size_m",
	    "min_cut_size_m",
	    "max_size_m",
	    "proposal_min_neighbors",
	    "border_px",
	    "channel",
	    "shape_model",
	    "min_shape_score",
	    "max_stages",
	    "segment_candidates",
	    "cascade_support",
	    "back_wall_length_m",
	    "max_continuing_share",
	    "min_separation_m",
	    "grow_m"};
	return keys;
}

void CascadeDetector::TClassOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& c, const std::string& s)
{
	checkKnownKeys(c, s, knownKeys());
	TClassOptions o = *this;
	o.cascade = c.read_string(s, "cascade", cascade, false);
	if (o.cascade.empty())
		throw ConfigError("[" + s + "] cascade must name a cascade XML file");
	constexpr double deg = M_PI / 180.0;
	o.upscale = readChecked(c, s, "upscale", upscale, 0.25, 8.0);
	o.minElevation =
	    readChecked(c, s, "min_elevation_deg", minElevation / deg, -90, 90) *
	    deg;
	o.maxElevation =
	    readChecked(c, s, "max_elevation_deg", maxElevation / deg, -90, 90) *
	    deg;
	o.farUpscale = readChecked(c, s, "far_upscale", farUpscale, 0, 8.0);
	o.farBelowPx = readChecked(c, s, "far_below_px", farBelowPx, 0, 10000);
	o.farMinElevation =
	    readChecked(
	        c, s, "far_min_elevation_deg", farMinElevation / deg, -90, 90) *
	    deg;
	o.farMaxElevation =
	    readChecked(
	        c, s, "far_max_elevation_deg", farMaxElevation / deg, -90, 90) *
	    deg;
	o.scaleFactor = readChecked(c, s, "scale_factor", scaleFactor, 1.01, 3.0);
	o.minNeighbors =
	    readCheckedInt(c, s, "min_neighbors", minNeighbors, 0, 100);
	o.windowStep = readCheckedInt(c, s, "window_step", windowStep, 0, 8);
	o.maxSizePx = readChecked(c, s, "max_size_px", maxSizePx, 0, 10000);
	o.minWidth = readChecked(c, s, "min_width_m", minWidth, 0, 100);
	o.maxWidth = readChecked(c, s, "max_width_m", maxWidth, 0, 100);
	o.minTop = readChecked(c, s, "min_top_m", minTop, -10, 100);
	o.maxTop = readChecked(c, s, "max_top_m", maxTop, -10, 100);
	o.maxDepth = readChecked(c, s, "max_depth_m", maxDepth, 0.01, 100);
	o.minPoints = readCheckedInt(c, s, "min_points", minPoints, 1, 1000000);
	o.minSize = readChecked(c, s, "min_size_m", minSize, 0.01, 100);
	o.minCutSize = readChecked(c, s, "min_cut_size_m", minCutSize, 0.01, 100);
	o.maxSize = readChecked(c, s, "max_size_m", maxSize, 0.01, 100);
	o.proposalMinNeighbors = readCheckedInt(
	    c, s, "proposal_min_neighbors", proposalMinNeighbors, -1, 100);
	o.borderPx = readChecked(c, s, "border_px", borderPx, 0, 1000);
	o.shapeModel = c.read_string(s, "shape_model", shapeModel, false);
	o.minShapeScore = readChecked(c, s, "min_shape_score", minShapeScore, 0, 1);
	o.maxStages = readCheckedInt(c, s, "max_stages", maxStages, 0, 1000);
	o.segmentCandidates =
	    readCheckedBool(c, s, "segment_candidates", segmentCandidates);
	o.cascadeSupport = readCheckedBool(c, s, "cascade_support", cascadeSupport);
	o.backWallLength =
	    readChecked(c, s, "back_wall_length_m", backWallLength, 0, 100);
	o.maxContinuingShare =
	    readChecked(c, s, "max_continuing_share", maxContinuingShare, 0, 1);
	o.minSeparation =
	    readChecked(c, s, "min_separation_m", minSeparation, 0, 100);
	o.grow = readChecked(c, s, "grow_m", grow, 0, 10);
	if (c.keyExists(s, "channel"))
	{
		try
		{
			o.channel = channelFromName(c.read_string(s, "channel", "", true));
		}
		catch (const ConfigError& e)
		{
			throw ConfigError("[" + s + "] channel: " + e.what());
		}
	}
	if (o.minWidth > o.maxWidth || o.minTop > o.maxTop ||
	    o.minSize > o.maxSize || o.minCutSize > o.maxSize ||
	    o.minElevation >= o.maxElevation ||
	    (o.farUpscale > 0 && o.farMinElevation >= o.farMaxElevation))
		throw ConfigError("[" + s + "] a minimum exceeds its maximum");
	*this = o;
}

void CascadeDetector::TClassOptions::saveToConfigFile(
    mrpt::config::CConfigFileBase& c, const std::string& s) const
{
	c.write(s, "cascade", cascade);
	constexpr double deg = M_PI / 180.0;
	c.write(s, "upscale", num(upscale));
	c.write(s, "min_elevation_deg", num(minElevation / deg));
	c.write(s, "max_elevation_deg", num(maxElevation / deg));
	c.write(s, "far_upscale", num(farUpscale));
	c.write(s, "far_below_px", num(farBelowPx));
	c.write(s, "far_min_elevation_deg", num(farMinElevation / deg));
	c.write(s, "far_max_elevation_deg", num(farMaxElevation / deg));
	c.write(s, "scale_factor", num(scaleFactor));
	c.write(s, "min_neighbors", std::to_string(minNeighbors));
	c.write(s, "window_step", std::to_string(windowStep));
	c.write(s, "max_size_px", num(maxSizePx));
	c.write(s, "min_width_m", num(minWidth));
	c.write(s, "max_width_m", num(maxWidth));
	c.write(s, "min_top_m", num(minTop));
	c.write(s, "max_top_m", num(maxTop));
	c.write(s, "max_depth_m", num(maxDepth));
	c.write(s, "min_points", std::to_string(minPoints));
	c.write(s, "min_size_m", num(minSize));
	c.write(s, "min_cut_size_m", num(minCutSize));
	c.write(s, "max_size_m", num(maxSize));
	c.write(s, "proposal_min_neighbors", std::to_string(proposalMinNeighbors));
	c.write(s, "border_px", num(borderPx));
	if (channel) c.write(s, "channel", channelName(*channel));
	c.write(s, "shape_model", shapeModel);
	c.write(s, "min_shape_score", num(minShapeScore));
	c.write(s, "max_stages", std::to_string(maxStages));
	writeBool(c, s, "segment_candidates", segmentCandidates);
	writeBool(c, s, "cascade_support", cascadeSupport);
	c.write(s, "back_wall_length_m", num(backWallLength));
	c.write(s, "max_continuing_share", num(maxContinuingShare));
	c.write(s, "min_separation_m", num(minSeparation));
	c.write(s, "grow_m", num(grow));
}

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
	// Built-in defaults for the paper's three classes (config/cascade.ini
	// holds the tuned values).
	TClassOptions wb(Label::Washbasin);
	wb.upscale = 1.0;
	wb.farUpscale = 2.5;
	wb.farBelowPx = 24;
	wb.minWidth = 0.25;
	wb.maxWidth = 0.9;
	wb.minTop = 0.6;
	wb.maxTop = 1.1;
	wb.maxDepth = 0.6;
	wb.minSize = 0.7;
	wb.minCutSize = 0.35;
	wb.maxSize = 1.2;
	TClassOptions bin(Label::Wastebasket);
	bin.upscale = 1.0;
	bin.farUpscale = 3.0;
	bin.farBelowPx = 24;
	bin.minWidth = 0.12;
	bin.maxWidth = 0.55;
	bin.minTop = 0.2;
	bin.maxTop = 0.65;
	bin.maxDepth = 0.45;
	bin.minSize = 0.28;
	bin.minCutSize = 0.2;
	bin.maxSize = 0.6;
	TClassOptions st(Label::Stairs);
	st.upscale = 1.0;
	st.minWidth = 0.6;
	st.maxWidth = 2.2;
	st.minTop = 0.25;
	st.maxTop = 2.0;
	st.maxDepth = 2.5;
	st.minSize = 0.8;
	st.minCutSize = 0.6;
	st.maxSize = 3.0;
	classes = {wb, bin, st};
}

const std::vector<std::string>& CascadeDetector::TOptions::knownKeys()
{
	static const std::vector<std::string> keys{
	    "channel",
	    "normal_smoothing_px",
	    "projection",
	    "classes",
	    "label_pixels",
	    "floor_tolerance_m",
	    "measure_margin",
	    "connected_object",
	    "proposals",
	    "proposal_min_pixels",
	    "proposal_join_px",
	    "proposal_max_height_m",
	    "proposal_margin",
	    "proposal_size_slack",
	    "proposal_foot_height_m",
	    "proposal_fill",
	    "proposal_range_gap_m",
	    "proposal_top_margin_m",
	    "proposal_size_check",
	    "range_scales",
	    "range_scale_slack",
	    "range_cut_m",
	    "range_objects_only",
	    "segment_range_gap_m",
	    "segment_max_taller",
	    "segment_range_window",
	    "threads"};
	return keys;
}

void CascadeDetector::TOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& c, const std::string& s)
{
	checkKnownKeys(c, s, knownKeys());
	TOptions o = *this;
	try
	{
		o.channel = channelFromName(
		    c.read_string(s, "channel", channelName(channel), false));
	}
	catch (const ConfigError& e)
	{
		throw ConfigError("[" + s + "] channel: " + e.what());
	}
	o.normalSmoothing =
	    readCheckedInt(c, s, "normal_smoothing_px", normalSmoothing, 0, 10);
	const std::string proj = c.read_string(
	    s, "projection", panoramic ? "panoramic" : "sweep", false);
	if (proj != "panoramic" && proj != "sweep")
		throw ConfigError(
		    "[" + s + "] projection = '" + proj +
		    "' must be panoramic or sweep");
	o.panoramic = proj == "panoramic";
	o.labelPixels = readCheckedBool(c, s, "label_pixels", labelPixels);
	o.floorTolerance =
	    readChecked(c, s, "floor_tolerance_m", floorTolerance, 0, 1);
	o.measureMargin = readChecked(c, s, "measure_margin", measureMargin, 0, 2);
	o.connectedObject =
	    readCheckedBool(c, s, "connected_object", connectedObject);
	o.proposals = readCheckedBool(c, s, "proposals", proposals);
	o.proposalMinPixels = readCheckedInt(
	    c, s, "proposal_min_pixels", proposalMinPixels, 1, 1000000);
	o.proposalJoinPx =
	    readCheckedInt(c, s, "proposal_join_px", proposalJoinPx, 0, 20);
	o.proposalMaxHeight =
	    readChecked(c, s, "proposal_max_height_m", proposalMaxHeight, 0.05, 20);
	o.proposalMargin =
	    readChecked(c, s, "proposal_margin", proposalMargin, 0, 5);
	o.proposalSizeSlack =
	    readChecked(c, s, "proposal_size_slack", proposalSizeSlack, 1, 10);
	o.proposalFootHeight =
	    readChecked(c, s, "proposal_foot_height_m", proposalFootHeight, 0, 5);
	o.proposalFill = readChecked(c, s, "proposal_fill", proposalFill, 0, 1);
	o.proposalRangeGap =
	    readChecked(c, s, "proposal_range_gap_m", proposalRangeGap, 0, 100);
	o.proposalTopMargin =
	    readChecked(c, s, "proposal_top_margin_m", proposalTopMargin, 0, 10);
	o.proposalSizeCheck =
	    readCheckedBool(c, s, "proposal_size_check", proposalSizeCheck);
	o.rangeScales = readCheckedBool(c, s, "range_scales", rangeScales);
	o.rangeScaleSlack =
	    readChecked(c, s, "range_scale_slack", rangeScaleSlack, 1, 10);
	o.rangeCut = readChecked(c, s, "range_cut_m", rangeCut, 0, 100);
	o.rangeObjectsOnly =
	    readCheckedBool(c, s, "range_objects_only", rangeObjectsOnly);
	o.segmentRangeGap =
	    readChecked(c, s, "segment_range_gap_m", segmentRangeGap, 0, 100);
	o.segmentMaxTaller =
	    readChecked(c, s, "segment_max_taller", segmentMaxTaller, 0, 1e6);
	o.segmentRangeWindow =
	    readCheckedBool(c, s, "segment_range_window", segmentRangeWindow);
	o.threads = readCheckedInt(c, s, "threads", threads, 0, 64);
	std::string list;
	for (const auto& k : classes) list += labelName(k.label) + " ";
	list = c.read_string(s, "classes", list, false);
	std::istringstream in(list);
	std::vector<TClassOptions> loaded;
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
		TClassOptions k(l);
		for (const auto& d : classes)
			if (d.label == l) k = d;  // defaults of a known class
		k.loadFromConfigFile(c, s + "." + name);
		loaded.push_back(k);
	}
	o.classes = loaded;
	*this = o;
}

void CascadeDetector::TOptions::saveToConfigFile(
    mrpt::config::CConfigFileBase& c, const std::string& s) const
{
	c.write(s, "channel", channelName(channel));
	c.write(s, "normal_smoothing_px", std::to_string(normalSmoothing));
	c.write(s, "projection", std::string(panoramic ? "panoramic" : "sweep"));
	std::string list;
	for (const auto& k : classes)
		list += (list.empty() ? "" : " ") + labelName(k.label);
	c.write(s, "classes", list);
	writeBool(c, s, "label_pixels", labelPixels);
	c.write(s, "floor_tolerance_m", num(floorTolerance));
	c.write(s, "measure_margin", num(measureMargin));
	writeBool(c, s, "connected_object", connectedObject);
	writeBool(c, s, "proposals", proposals);
	c.write(s, "proposal_min_pixels", std::to_string(proposalMinPixels));
	c.write(s, "proposal_join_px", std::to_string(proposalJoinPx));
	c.write(s, "proposal_max_height_m", num(proposalMaxHeight));
	c.write(s, "proposal_margin", num(proposalMargin));
	c.write(s, "proposal_size_slack", num(proposalSizeSlack));
	c.write(s, "proposal_foot_height_m", num(proposalFootHeight));
	c.write(s, "proposal_fill", num(proposalFill));
	c.write(s, "proposal_range_gap_m", num(proposalRangeGap));
	c.write(s, "proposal_top_margin_m", num(proposalTopMargin));
	writeBool(c, s, "proposal_size_check", proposalSizeCheck);
	writeBool(c, s, "range_scales", rangeScales);
	c.write(s, "range_scale_slack", num(rangeScaleSlack));
	c.write(s, "range_cut_m", num(rangeCut));
	writeBool(c, s, "range_objects_only", rangeObjectsOnly);
	c.write(s, "segment_range_gap_m", num(segmentRangeGap));
	c.write(s, "segment_max_taller", num(segmentMaxTaller));
	writeBool(c, s, "segment_range_window", segmentRangeWindow);
	c.write(s, "threads", std::to_string(threads));
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
