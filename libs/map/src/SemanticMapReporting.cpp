/* semnav: semantic navigation from tilting-laser sweeps */
// SemanticMap's reporting rules: which candidates are the map's objects
// (reported(), unreportedReason()), the rules for cascade objects whose
// shape check was not sure (doubtfulObjectReason()) and what makes a door
// sure (doorLeafScore()) (docs/mapping.md, "Objects in the map").
#include <mrpt/core/bits_math.h>
#include <semnav/common/ClassRegistry.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/perception/LabeledRegion.h>

#include <algorithm>
#include <cmath>

namespace semnav
{
ClassInfo::Plausibility SemanticMap::plausibility(Label l) const
{
	ClassInfo::Plausibility p = classInfo(l).plausibility;
	switch (l)
	{
		case Label::Door:
			p.minHeight = m_options.doorMinHeight;
			break;
		case Label::Stairs:
			p.maxBottom = m_options.stairsMaxBottom;
			break;
		case Label::Washbasin:
			p.minInstanceTop = m_options.washbasinMinTop;
			p.maxWallDistance = m_options.washbasinMaxWallDistance;
			break;
		default:
			break;
	}
	return p;
}

bool SemanticMap::reported(const ObjectInstance& o) const
{
	return unreportedReason(o).empty();
}

std::string SemanticMap::unreportedReason(const ObjectInstance& o) const
{
	// Region classes (doors) are no detections: no shape score; their
	// views are door views (doorInView()).
	const bool region =
	    classInfo(o.label).instances == ClassInfo::InstanceSource::Regions;
	const bool sure = sureDetection(o);
	int minObs =
	    region ? m_options.doorMinObservations : m_options.minObservations;
	const char* obsKey = region ? "door_min_observations" : "min_observations";
	const bool fair = m_options.unsureOnceMinShapeScore > 0 &&
	                  o.bestShapeScore >= m_options.unsureOnceMinShapeScore;
	if (!region && !sure && !fair && m_options.unsureMinObservations > minObs)
	{
		minObs = m_options.unsureMinObservations;
		obsKey = "unsure_min_observations";
	}
	if (static_cast<int>(o.observations) < minObs) return obsKey;
	double ratio = o.label == Label::Stairs ? m_options.stairsMinDetectionRatio
	                                        : m_options.minDetectionRatio;
	const char* ratioKey = o.label == Label::Stairs
	                           ? "stairs_min_detection_ratio"
	                           : "min_detection_ratio";
	if (sure && m_options.sureMinDetectionRatio < ratio)
	{
		ratio = m_options.sureMinDetectionRatio;
		ratioKey = "sure_min_detection_ratio";
	}
	if (region)
	{
		ratio = m_options.doorMinDetectionRatio;
		ratioKey = "door_min_detection_ratio";
		if (o.bestShapeScore >= m_options.sureShapeScore &&
		    m_options.doorSureMinDetectionRatio < ratio)
		{
			ratio = m_options.doorSureMinDetectionRatio;
			ratioKey = "door_sure_min_detection_ratio";
		}
	}
	if (static_cast<double>(o.observations) <
	    ratio * static_cast<double>(o.views))
		return ratioKey;
	if (!region && !sure)
	{
		const std::string doubtful = doubtfulObjectReason(o);
		if (!doubtful.empty()) return doubtful;
	}
	if (region && m_options.doorMinWidth > 0 && !o.sightingSizes.empty() &&
	    std::none_of(
	        o.sightingSizes.begin(), o.sightingSizes.end(),
	        [&](const mrpt::math::TPoint3D& s)
	        { return s.x >= m_options.doorMinWidth; }))
		return "door_min_width_m";
	const ClassInfo::Plausibility p = plausibility(o.label);
	double maxBottom = p.maxBottom;
	if (o.label == Label::Stairs && sure && m_options.sureStairsMaxBottom > 0)
		maxBottom = std::max(maxBottom, m_options.sureStairsMaxBottom);
	// The keys of the plausibility rules plausibility() sets from the
	// options; the class registry's own bounds otherwise.
	const bool door = o.label == Label::Door;
	const bool stairs = o.label == Label::Stairs;
	const bool basin = o.label == Label::Washbasin;
	if (o.extent().z < p.minHeight)
		return door ? "door_min_height_m" : "the class's least height";
	if (o.minCorner.z > maxBottom)
		return stairs
		           ? (sure ? "sure_stairs_max_bottom_m" : "stairs_max_bottom_m")
		           : "the class's highest bottom";
	if (o.maxCorner.z < p.minInstanceTop)
		return basin ? "washbasin_min_top_m" : "the class's lowest top";
	if (p.maxWallDistance > 0 &&
	    !wallWithin(o.centroid.x, o.centroid.y, p.maxWallDistance))
		return basin ? "washbasin_max_wall_distance_m"
		             : "the class's wall distance";
	return {};
}

bool SemanticMap::wallWithin(double x, double y, double radius) const
{
	const auto& labels = get(kLabels);
	const GridGeometry& g = m_geometry;
	const int r = static_cast<int>(std::ceil(radius / g.resolution));
	int cx, cy;
	if (!g.worldToCell(x, y, cx, cy)) return false;
	for (int dy = -r; dy <= r; dy++)
		for (int dx = -r; dx <= r; dx++)
		{
			if (!g.contains(cy + dy, cx + dx)) continue;
			if (std::hypot(g.centerX(cx + dx) - x, g.centerY(cy + dy) - y) >
			    radius)
				continue;
			const LabelSet ls(static_cast<LabelSet::mask_t>(
			    labels[g.index(cy + dy, cx + dx)]));
			if (ls.contains(Label::Wall)) return true;
		}
	return false;
}

std::string SemanticMap::doubtfulObjectReason(const ObjectInstance& o) const
{
	const auto& sizes = o.sightingSizes;
	// A flight is wide; a box or a cabinet taken for one is not.
	if (o.label == Label::Stairs && m_options.unsureStairsMinWidth > 0 &&
	    !sizes.empty() &&
	    ObjectInstance::median(sizes, &mrpt::math::TPoint3D::x) <
	        m_options.unsureStairsMinWidth)
		return "unsure_stairs_min_width_m";
	// A wastebasket is seen narrow at least once; a plant pot, whose
	// foliage is wider than its pot, never (nor does it score as well).
	const double wideScore = m_options.unsureWastebasketWideMinShapeScore;
	if (o.label == Label::Wastebasket &&
	    m_options.unsureWastebasketMaxWidth > 0 && !sizes.empty() &&
	    (wideScore <= 0 || o.bestShapeScore < wideScore) &&
	    std::none_of(
	        sizes.begin(), sizes.end(),
	        [&](const mrpt::math::TPoint3D& s)
	        { return s.x <= m_options.unsureWastebasketMaxWidth; }))
		return "unsure_wastebasket_max_width_m";
	// One object is not two: a sure object of another label stands there.
	if (m_options.unsureOtherLabelDistance <= 0) return {};
	const bool nearSure = std::any_of(
	    m_instances.begin(), m_instances.end(),
	    [&](const ObjectInstance& q)
	    {
		    return q.label != o.label && sureDetection(q) &&
		           std::hypot(
		               q.centroid.x - o.centroid.x,
		               q.centroid.y - o.centroid.y) <=
		               m_options.unsureOtherLabelDistance &&
		           reported(q);
	    });
	return nearSure ? "unsure_other_label_distance_m" : std::string();
}

bool SemanticMap::sureDetection(const ObjectInstance& o) const
{
	return classInfo(o.label).instances ==
	           ClassInfo::InstanceSource::Detections &&
	       o.bestShapeScore >= m_options.sureShapeScore;
}

double SemanticMap::doorLeafScore(const LabeledRegion& reg) const
{
	// Robot frame: the line of sight to the region against its normal.
	const double sight = std::hypot(reg.centroid.x, reg.centroid.y);
	const double normal = std::hypot(reg.meanNormal.x, reg.meanNormal.y);
	if (sight < 1e-6 || normal < 1e-6) return 0;
	const double cosIncidence = std::abs(
	                                reg.centroid.x * reg.meanNormal.x +
	                                reg.centroid.y * reg.meanNormal.y) /
	                            (sight * normal);
	if (cosIncidence <
	    std::cos(mrpt::DEG2RAD(m_options.doorSureMaxIncidenceDeg)))
		return 0;
	const auto share = [](double size, double whole)
	{ return whole > 0 ? std::min(1.0, size / whole) : 1.0; };
	return share(reg.width, m_options.doorSureMinWidth) *
	       share(reg.height, m_options.doorSureMinHeight);
}

}  // namespace semnav
