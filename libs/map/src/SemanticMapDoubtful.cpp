/* semnav: semantic navigation from tilting-laser sweeps */
// SemanticMap::doubtfulObjectPlausible(): the reporting rules for cascade
// objects whose shape check was not sure (docs/mapping.md, "Objects in the
// map").
#include <semnav/common/ClassRegistry.h>
#include <semnav/map/SemanticMap.h>

#include <algorithm>
#include <cmath>

namespace semnav
{
bool SemanticMap::doubtfulObjectPlausible(const ObjectInstance& o) const
{
	const auto& sizes = o.sightingSizes;
	// A flight is wide; a box or a cabinet taken for one is not.
	if (o.label == Label::Stairs && m_options.unsureStairsMinWidth > 0 &&
	    !sizes.empty() &&
	    ObjectInstance::median(sizes, &mrpt::math::TPoint3D::x) <
	        m_options.unsureStairsMinWidth)
		return false;
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
		return false;
	// One object is not two: a sure object of another label stands there.
	if (m_options.unsureOtherLabelDistance <= 0) return true;
	return std::none_of(
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
}

bool SemanticMap::sureDetection(const ObjectInstance& o) const
{
	return classInfo(o.label).instances ==
	           ClassInfo::InstanceSource::Detections &&
	       o.bestShapeScore >= m_options.sureShapeScore;
}

}  // namespace semnav
