/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/LabelSet.h>
#include <semnav/common/OptionTable.h>
#include <semnav/localization/ObjectFootprints.h>
#include <semnav/localization/SemanticEvidenceMap.h>
#include <semnav/localization/SemanticExtractor.h>
#include <semnav/localization/WallMap.h>
#include <semnav/map/SemanticMap.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>

namespace semnav
{
namespace
{
using O = SemanticEvidenceMap::TOptions;
const OptionTable<O>& optionTable()
{
	static const auto t =
	    OptionTable<O>()
	        .real(
	            "class_points", &O::classPoints, 0, 1000,
	            "Weight of the class points (door, stairs, washbasin, ...) "
	            "in effective points; 0: off.")
	        .real(
	            "ground_points", &O::groundPoints, 0, 1000,
	            "Weight of the ground points (floor, sidewalk, grass, "
	            "obstacle); 0: off.")
	        .real(
	            "object_points", &O::objectPoints, 0, 1000,
	            "Weight of the detected objects against the map's "
	            "instances; 0: off.")
	        .real(
	            "sigma_m", &O::sigma, 0.01, 10,
	            "Class and ground points: std dev of the distance to the "
	            "nearest map cell of their label...")
	        .real(
	            "max_distance_m", &O::maxDistance, 0.01, 100,
	            "...clamped here.")
	        .real(
	            "object_sigma_m", &O::objectSigma, 0.01, 10,
	            "Objects: std dev of the distance to the nearest instance of "
	            "their label...")
	        .real(
	            "object_max_distance_m", &O::objectMaxDistance, 0.01, 100,
	            "...clamped here.")
	        .real(
	            "hit_weight", &O::hitWeight, 0, 1,
	            "Mixture weight of the Gaussian part...")
	        .real(
	            "random_weight", &O::randomWeight, 1e-6, 1,
	            "...and of the uniform part.")
	        .real(
	            "unknown_weight", &O::unknownWeight, 1e-6, 1,
	            "Likelihood of a point in a cell the map never observed.")
	        .flag(
	            "mapping_flat_labels_only", &O::mappingFlatLabelsOnly,
	            "Mapping: score only the flat labels (floor, sidewalk, "
	            "grass); obstacle and class points are surfaces seen from one "
	            "side and pull each estimate back toward earlier views.");
	return t;
}
}  // namespace

SEMNAV_OPTIONS_FROM_TABLE(SemanticEvidenceMap::TOptions, optionTable())

float SemanticEvidenceMap::value(double d, double sigma, double maxD) const
{
	return WallMap::mixtureLogLikelihood(
	    d, sigma, maxD, m_options.hitWeight, m_options.randomWeight);
}

void SemanticEvidenceMap::build(const SemanticMap& map, bool flatOnly)
{
	m_geometry = map.geometry();
	const float unknown = static_cast<float>(std::log(m_options.unknownWeight));
	const float far = value(m_options.maxDistance, m_options.sigma, 1e9);
	m_outside = std::max(far, unknown);
	for (auto& f : m_fields) f.clear();
	const std::vector<float>& observations = map.get("observations");
	const std::vector<float>& labels = map.get("labels");
	m_unknown.assign(m_geometry.cellCount(), 0);
	LabelSet::mask_t present = 0;
	for (std::size_t i = 0; i < m_unknown.size(); i++)
	{
		m_unknown[i] = observations[i] > 0 ? 0 : 1;
		present |= static_cast<LabelSet::mask_t>(labels[i]);
	}
	for (const Label l : allLabels())
	{
		if (!scored(l, flatOnly) || !LabelSet(present).contains(l)) continue;
		m_fields[static_cast<std::size_t>(l)].resize(m_geometry.cellCount());
		computeField(l, labels, CellRect::all(m_geometry));
	}
	takeObjects(map);
	m_source = &map;
	m_version = map.version();
	m_flatOnly = flatOnly;
	m_labels = labels;
	m_present = present;
}

bool SemanticEvidenceMap::scored(Label l, bool flatOnly)
{
	const bool flat =
	    SemanticExtractor::isGroundLabel(l) && l != Label::Obstacle;
	return (SemanticExtractor::isClassLabel(l) ||
	        SemanticExtractor::isGroundLabel(l)) &&
	       (!flatOnly || flat);
}

void SemanticEvidenceMap::takeObjects(const SemanticMap& map)
{
	for (auto& o : m_objects) o.clear();
	for (const auto& o : map.instances())
		m_objects[static_cast<std::size_t>(o.label)].push_back(
		    {o.centroid.x, o.centroid.y});
}

void SemanticEvidenceMap::computeField(
    Label l, const std::vector<float>& labels, const CellRect& cells)
{
	// A cell's value depends on the cells of label l within max_distance
	// only (farther, the distance is clamped): the distance transform of
	// the window around `cells` gives the whole map's there.
	const int reach = static_cast<int>(std::ceil(
	                      m_options.maxDistance / m_geometry.resolution)) +
	                  1;
	const CellRect out = cells.dilated(reach).clipped(m_geometry);
	const CellRect in = out.dilated(reach).clipped(m_geometry);
	if (out.empty()) return;
	const int w = in.col1 - in.col0, h = in.row1 - in.row0;
	cv::Mat src(h, w, CV_8U, cv::Scalar(255));
	for (int r = 0; r < h; r++)
	{
		uint8_t* row = src.ptr<uint8_t>(r);
		const float* lab = &labels[m_geometry.index(in.row0 + r, in.col0)];
		for (int c = 0; c < w; c++)
			if (LabelSet(static_cast<LabelSet::mask_t>(lab[c])).contains(l))
				row[c] = 0;
	}
	cv::Mat dist;
	cv::distanceTransform(src, dist, cv::DIST_L2, cv::DIST_MASK_PRECISE);
	const float unknown = static_cast<float>(std::log(m_options.unknownWeight));
	auto& field = m_fields[static_cast<std::size_t>(l)];
	for (int cy = out.row0; cy < out.row1; cy++)
	{
		const float* d = dist.ptr<float>(cy - in.row0) - in.col0;
		for (int cx = out.col0; cx < out.col1; cx++)
		{
			const std::size_t i = m_geometry.index(cy, cx);
			const float v = value(
			    d[cx] * m_geometry.resolution, m_options.sigma,
			    m_options.maxDistance);
			field[i] = m_unknown[i] ? std::max(v, unknown) : v;
		}
	}
}

SemanticObservation SemanticEvidenceMap::observedPart(
    double x, double y, double yaw, const SemanticObservation& obs) const
{
	SemanticObservation out;
	if (empty()) return out;
	const double c = std::cos(yaw), s = std::sin(yaw);
	const bool flatOnly = m_options.mappingFlatLabelsOnly;
	const auto isFlat = [](Label l)
	{ return SemanticExtractor::isGroundLabel(l) && l != Label::Obstacle; };
	const auto keep = [&](const std::vector<SemanticSample>& in,
	                      std::vector<SemanticSample>& dst)
	{
		for (const auto& p : in)
		{
			int cx = 0, cy = 0;
			if (!hasField(p.label) || (flatOnly && !isFlat(p.label)) ||
			    !m_geometry.worldToCell(
			        x + c * p.x - s * p.y, y + s * p.x + c * p.y, cx, cy) ||
			    m_unknown[m_geometry.index(cy, cx)])
				continue;
			dst.push_back(p);
		}
	};
	if (!flatOnly) keep(obs.classSamples, out.classSamples);
	keep(obs.groundSamples, out.groundSamples);
	for (const auto& o : obs.objects)
		if (!m_objects[static_cast<std::size_t>(o.label)].empty())
			out.objects.push_back(o);
	return out;
}

double SemanticEvidenceMap::meanField(
    double x, double y, double c, double s,
    const std::vector<SemanticSample>& pts, bool knownOnly) const
{
	double sum = 0;
	std::size_t n = 0;
	const double inv = 1.0 / m_geometry.resolution;
	for (const auto& p : pts)
	{
		const auto& f = m_fields[static_cast<std::size_t>(p.label)];
		if (f.empty()) continue;
		const double wx = x + c * p.x - s * p.y, wy = y + s * p.x + c * p.y;
		const int cx =
		    static_cast<int>(std::floor((wx - m_geometry.originX) * inv));
		const int cy =
		    static_cast<int>(std::floor((wy - m_geometry.originY) * inv));
		const bool inside = m_geometry.contains(cy, cx);
		if (knownOnly && (!inside || m_unknown[m_geometry.index(cy, cx)]))
			continue;
		sum += inside ? f[m_geometry.index(cy, cx)] : m_outside;
		n++;
	}
	return n ? sum / double(n) : 0.0;
}

double SemanticEvidenceMap::meanObjects(
    double x, double y, double c, double s,
    const std::vector<SemanticSample>& objects) const
{
	double sum = 0;
	std::size_t n = 0;
	for (const auto& o : objects)
	{
		const auto& inst = m_objects[static_cast<std::size_t>(o.label)];
		if (inst.empty()) continue;
		const double wx = x + c * o.x - s * o.y, wy = y + s * o.x + c * o.y;
		double best = std::numeric_limits<double>::infinity();
		for (const auto& q : inst)
			best = std::min(best, std::hypot(q.x - wx, q.y - wy));
		sum += value(best, m_options.objectSigma, m_options.objectMaxDistance);
		n++;
	}
	return n ? sum / double(n) : 0.0;
}

SemanticEvidenceMap::Terms SemanticEvidenceMap::terms(
    double x, double y, double yaw, const SemanticObservation& obs) const
{
	return termsOf(x, y, yaw, obs, false);
}

SemanticEvidenceMap::Terms SemanticEvidenceMap::knownTerms(
    double x, double y, double yaw, const SemanticObservation& obs) const
{
	return termsOf(x, y, yaw, obs, true);
}

SemanticEvidenceMap::Terms SemanticEvidenceMap::termsOf(
    double x, double y, double yaw, const SemanticObservation& obs,
    bool knownOnly) const
{
	Terms t;
	if (empty()) return t;
	const double c = std::cos(yaw), s = std::sin(yaw);
	if (m_options.classPoints > 0)
		t.classes = m_options.classPoints *
		            meanField(x, y, c, s, obs.classSamples, knownOnly);
	if (m_options.groundPoints > 0)
		t.ground = m_options.groundPoints *
		           meanField(x, y, c, s, obs.groundSamples, knownOnly);
	if (m_options.objectPoints > 0)
		t.objects =
		    m_options.objectPoints * meanObjects(x, y, c, s, obs.objects);
	if (m_footprints)
		t.footprints = m_footprints->logLikelihood(x, y, yaw, obs.footprints);
	return t;
}

double SemanticEvidenceMap::logLikelihood(
    double x, double y, double yaw, const SemanticObservation& obs) const
{
	return terms(x, y, yaw, obs).total();
}

}  // namespace semnav
