/* semnav: semantic navigation from tilting-laser sweeps */
// WallMap: the walls of a semantic map's cells (Hough segments), and the
// updates of a wall map after the map changed, around what changed only.
#include <semnav/localization/WallMap.h>
#include <semnav/map/SemanticMap.h>

#include <opencv2/imgproc.hpp>

namespace semnav
{
CellRect WallMap::readSemanticMap(const SemanticMap& map, const CellRect& cells)
{
	const auto& labels = map.get("labels");
	const auto& observations = map.get("observations");
	CellRect changed;
	for (int cy = cells.row0; cy < cells.row1; cy++)
		for (int cx = cells.col0; cx < cells.col1; cx++)
		{
			const std::size_t i = m_geometry.index(cy, cx);
			const uint8_t wall =
			    LabelSet(static_cast<LabelSet::mask_t>(labels[i]))
			        .contains(Label::Wall);
			bool flipped = wall != m_wallMask[i];
			m_wallMask[i] = wall;
			if (!m_unknownMask.empty())
			{
				const uint8_t unknown = observations[i] > 0 ? 0 : 1;
				flipped = flipped || unknown != m_unknownMask[i];
				m_unknownMask[i] = unknown;
			}
			if (flipped) changed.add(cy, cx);
		}
	return changed;
}

void WallMap::houghSegments()
{
	// Segments of the wall cells: probabilistic Hough transform over the
	// whole map (on tiles, the segments that end at tile borders changed
	// the main direction enough to change the particle filter's course).
	const cv::Mat mask(
	    m_geometry.rows, m_geometry.cols, CV_8U,
	    const_cast<uint8_t*>(m_wallMask.data()));
	std::vector<cv::Vec4i> lines;
	cv::HoughLinesP(
	    mask, lines, 1, CV_PI / 360, 15, 0.5 / m_geometry.resolution, 2);
	m_segments.clear();
	for (const auto& l : lines)
	{
		WallSegment s;
		s.p0 = {m_geometry.centerX(l[0]), m_geometry.centerY(l[1])};
		s.p1 = {m_geometry.centerX(l[2]), m_geometry.centerY(l[3])};
		m_segments.push_back(s);
	}
	m_main = MainDirections::estimate(m_segments, m_options.directions);
}

void WallMap::updateFromSemanticMap(
    const SemanticMap& map, bool unobservedUnknown)
{
	const SemanticMap::Changes changes = map.changesSince(m_version);
	if (!m_fromSemanticMap || m_source != &map || changes.all ||
	    !(map.geometry() == m_geometry) ||
	    unobservedUnknown == m_unknownMask.empty() || m_field.empty())
	{
		buildFromSemanticMap(map, unobservedUnknown);
		return;
	}
	const CellRect changed = readSemanticMap(map, changes.touched);
	computeField(changed);
	if (!changed.empty()) houghSegments();
	m_version = map.version();
}

void WallMap::update(const SemanticMap& observed)
{
	const SemanticMap::Changes changes = observed.changesSince(m_version);
	if (m_fromSemanticMap || m_source != &observed || changes.all ||
	    m_field.empty() || !(fieldGeometry(&observed) == m_geometry))
	{
		rebuild(&observed);
		return;
	}
	// The wall-map cells whose centres lie in the observed cells that
	// changed (one more around: rounding).
	const GridGeometry& og = observed.geometry();
	const CellRect& t = changes.touched;
	const double res = m_geometry.resolution;
	const auto col = [&](double x)
	{ return static_cast<int>(std::floor((x - m_geometry.originX) / res)); };
	const auto row = [&](double y)
	{ return static_cast<int>(std::floor((y - m_geometry.originY) / res)); };
	const CellRect seen =
	    t.empty()
	        ? CellRect()
	        : CellRect{row(og.originY + t.row0 * og.resolution) - 1, col(og.originX + t.col0 * og.resolution) - 1, row(og.originY + t.row1 * og.resolution) + 2, col(og.originX + t.col1 * og.resolution) + 2}
	              .clipped(m_geometry);
	const CellRect changed =
	    drawSegments(m_drawn).united(markUnknown(observed, seen));
	maskWalls(changed);
	computeField(changed);
	m_main = MainDirections::estimate(m_segments, m_options.directions);
	m_version = observed.version();
}

}  // namespace semnav
