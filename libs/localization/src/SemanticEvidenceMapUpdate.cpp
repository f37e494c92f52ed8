/* semnav: semantic navigation from tilting-laser sweeps */
// SemanticEvidenceMap::update(): the fields brought up to date with a grown
// map around what changed, with the result of a full build().
#include <semnav/common/LabelSet.h>
#include <semnav/localization/SemanticEvidenceMap.h>
#include <semnav/map/SemanticMap.h>

namespace semnav
{
void SemanticEvidenceMap::update(const SemanticMap& map, bool flatOnly)
{
	const SemanticMap::Changes changes = map.changesSince(m_version);
	if (m_source != &map || flatOnly != m_flatOnly || changes.all ||
	    !(map.geometry() == m_geometry))
	{
		build(map, flatOnly);
		return;
	}
	// Per label, the cells that gained or lost it; the cells observed for
	// the first time (their fields' unknown floor goes).
	const std::vector<float>& labels = map.get("labels");
	const std::vector<float>& observations = map.get("observations");
	std::array<CellRect, kMaxLabelCount> relabelled;
	CellRect observed;
	LabelSet::mask_t lost = 0, present = m_present;
	const CellRect& r = changes.touched;
	for (int cy = r.row0; cy < r.row1; cy++)
		for (int cx = r.col0; cx < r.col1; cx++)
		{
			const std::size_t i = m_geometry.index(cy, cx);
			const auto now = static_cast<LabelSet::mask_t>(labels[i]);
			const auto before = static_cast<LabelSet::mask_t>(m_labels[i]);
			if (now != before)
			{
				for (std::size_t b = 0; b < kMaxLabelCount; b++)
					if ((now ^ before) >> b & 1u) relabelled[b].add(cy, cx);
				lost |= before & ~now;
				present |= now;
				m_labels[i] = labels[i];
			}
			const uint8_t unknown = observations[i] > 0 ? 0 : 1;
			if (unknown != m_unknown[i])
			{
				m_unknown[i] = unknown;
				observed.add(cy, cx);
			}
		}
	m_version = map.version();
	// A label scored for the first time, or gone from a cell (writes the
	// tracking does not see): anew.
	LabelSet::mask_t newlyScored = 0;
	for (const Label l : allLabels())
		if (scored(l, flatOnly) && LabelSet(present & ~m_present).contains(l))
			newlyScored |= LabelSet::mask_t(1) << static_cast<unsigned>(l);
	if (lost || newlyScored)
	{
		build(map, flatOnly);
		return;
	}
	for (const Label l : allLabels())
	{
		const auto k = static_cast<std::size_t>(l);
		if (m_fields[k].empty()) continue;
		const CellRect cells = relabelled[k].united(observed);
		if (!cells.empty()) computeField(l, labels, cells);
	}
	m_present = present;
	takeObjects(map);
}

}  // namespace semnav
