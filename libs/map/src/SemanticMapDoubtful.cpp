/* semnav: semantic navigation from tilting-laser sweeps */
// SemanticMap::doubtfulObjectReason(): the reporting rules for cascade
// objects whose shape check was not sure; doorLeafScore(), what makes a door
// sure (docs/mapping.md, "Objects in the map").
#include <mrpt/core/bits_math.h>
#include <semnav/common/ClassRegistry.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/perception/LabeledRegion.h>

#include <algorithm>
#include <cmath>

namespace semnav
{
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
