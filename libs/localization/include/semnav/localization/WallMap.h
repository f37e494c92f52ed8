/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/math/TPoint2D.h>
#include <mrpt/poses/CPose2D.h>
#include <semnav/common/CellRect.h>
#include <semnav/common/GridGeometry.h>
#include <semnav/localization/MainDirections.h>
#include <semnav/localization/WallSegment.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace semnav
{
class SemanticMap;

/** The walls of the map, for localization: world-frame wall segments and a
 * likelihood field over them (per cell, log of
 * hitWeight * exp(-d^2 / 2 sigma^2) + randomWeight, d = distance to the
 * nearest wall), plus the map's main direction (modulo 90 deg).
 *
 * Built either from accumulated segments (mapping: each localized sweep's
 * walls added at its pose) or from a SemanticMap's cells labelled wall
 * (a known map; segments then come from a Hough transform of those cells).
 * INI section [WallMap]. */
class WallMap
{
public:
	struct TOptions : public mrpt::config::CLoadableOptions
	{
		void loadFromConfigFile(
		    const mrpt::config::CConfigFileBase& c,
		    const std::string& section) override;
		void saveToConfigFile(
		    mrpt::config::CConfigFileBase& c,
		    const std::string& section) const override;

		/** Likelihood field cell size (m). */
		double resolution = 0.05;
		/** Std dev of a wall sample's distance to the map wall (m). */
		double sigma = 0.08;
		/** Distances are clamped here (m). */
		double maxDistance = 0.5;
		/** Mixture weights of the hit and random parts. */
		double hitWeight = 0.9;
		double randomWeight = 0.1;
		/** Likelihood of a wall sample in a cell the map never observed
		 * (mapping: walls beyond what was seen so far). */
		double unknownWeight = 0.3;
		/** Segments go on this far into never-observed cells (m): a wall
		 * seen up to the edge of a view continues beyond it. */
		double unknownExtension = 1.0;
		/** Room around the walls (m). */
		double margin = 1.0;
		/** Main direction estimate (as WallExtractor). */
		MainDirections::TEstimateOptions directions{5.0 * M_PI / 180, 1.5, 0.4};
	};

	WallMap() = default;
	explicit WallMap(const TOptions& o) : m_options(o) {}

	/** Adds world-frame segments; call rebuild() before scoring. */
	void addSegments(const std::vector<WallSegment>& worldSegments);
	/** Adds robot-frame segments seen at `pose`. */
	void addObservation(
	    const std::vector<WallSegment>& robotSegments,
	    const mrpt::poses::CPose2D& pose);
	/** Recomputes the likelihood field and main direction from the
	 * segments. With `observed`, cells that map never observed score at
	 * least `unknownWeight` (a wall seen there is new, not a mismatch);
	 * without it every cell counts as observed. */
	void rebuild(const SemanticMap* observed = nullptr);
	/** Replaces the contents by the wall-labelled cells of a semantic map
	 * (likelihood field from the cells, segments from a probabilistic Hough
	 * transform of them). With `unobservedUnknown`, cells the map never
	 * observed score unknown_weight (as in rebuild() with a map): a map
	 * built from a few sweeps lacks walls that are there. */
	void buildFromSemanticMap(
	    const SemanticMap& map, bool unobservedUnknown = false);
	/** rebuild(&observed) after segments were added and `observed` grew
	 * since the last rebuild(&observed) or update(): the field recomputed
	 * around the new segments and the cells observed since only, with the
	 * result of rebuild(&observed). */
	void update(const SemanticMap& observed);
	/** buildFromSemanticMap() for `map` changed since the last
	 * buildFromSemanticMap() or updateFromSemanticMap() from it: the field
	 * recomputed around the cells whose wall label or observed state
	 * changed (SemanticMap::changesSince), the segments again when a wall
	 * cell changed; the result of buildFromSemanticMap(). */
	void updateFromSemanticMap(
	    const SemanticMap& map, bool unobservedUnknown = false);

	bool empty() const { return m_field.empty(); }
	const std::vector<WallSegment>& segments() const { return m_segments; }
	/** Main direction of the walls, in [-pi/4, pi/4), if they have one. */
	const std::optional<double>& mainDirection() const { return m_main; }
	const GridGeometry& geometry() const { return m_geometry; }
	/** The likelihood field, per cell of geometry(). */
	const std::vector<float>& field() const { return m_field; }

	/** Log-likelihood of one world point (outside the field: the
	 * clamped-distance value, or the unknown-cell value when built with an
	 * observed area). */
	float logLikelihood(double x, double y) const
	{
		const int cx = static_cast<int>((x - m_x0) * m_invRes);
		const int cy = static_cast<int>((y - m_y0) * m_invRes);
		if (x < m_x0 || y < m_y0 || cx >= m_nx || cy >= m_ny) return m_outside;
		return m_field[static_cast<std::size_t>(cy) * m_nx + cx];
	}
	/** Sum of logLikelihood over robot-frame points seen at a pose. */
	double logLikelihood(
	    double x, double y, double yaw,
	    const std::vector<mrpt::math::TPoint2D>& robotPoints) const;
	/** The sum over the points that fall in cells the map observed (all
	 * of them when built without an observed area); `known` counts them. */
	double knownLogLikelihood(
	    double x, double y, double yaw,
	    const std::vector<mrpt::math::TPoint2D>& robotPoints,
	    std::size_t& known) const;
	/** Fraction of the points within 2 sigma of a wall at the pose. */
	double inlierFraction(
	    const mrpt::poses::CPose2D& pose,
	    const std::vector<mrpt::math::TPoint2D>& robotPoints) const;
	/** The likelihood field's value at distance d from the nearest
	 * landmark: log(hit exp(-d^2 / 2 sigma^2) + random), d clamped at
	 * maxDistance (also the semantic evidence's fields). */
	static float mixtureLogLikelihood(
	    double d, double sigma, double maxDistance, double hit, double random);
	/** Log-likelihood of a point on a wall / far from walls. */
	float ceiling() const { return m_ceiling; }
	float floorValue() const { return m_floor; }

	const TOptions& options() const { return m_options; }

private:
	/** The field's geometry: the segments' extent (and the observed map's)
	 * with the margin. */
	GridGeometry fieldGeometry(const SemanticMap* observed) const;
	/** Draws the segments from index `from` on into the line and extension
	 * masks; returns the cells drawn (bounding box). */
	CellRect drawSegments(std::size_t from);
	/** Unknown mask from `observed` in `cells`; returns the cells that
	 * changed. */
	CellRect markUnknown(const SemanticMap& observed, const CellRect& cells);
	/** Wall mask from the line and extension masks in `cells`. */
	void maskWalls(const CellRect& cells);
	/** Wall (and unknown) masks from a semantic map's cells in `cells`;
	 * returns the cells whose wall label or unknown state changed. */
	CellRect readSemanticMap(const SemanticMap& map, const CellRect& cells);
	/** Segments of the wall mask (Hough), then the main direction. */
	void houghSegments();
	/** Constants and the field everywhere from the masks. */
	void buildField(bool withUnknown);
	/** The field in `cells` and around them, from the wall mask. */
	void computeField(const CellRect& cells);
	/** Cells of distance beyond which the field no longer changes. */
	int reach() const;
	float value(double d) const;

	TOptions m_options;
	std::vector<WallSegment> m_segments;
	std::optional<double> m_main;
	GridGeometry m_geometry;
	std::vector<float> m_field, m_distance;
	/** 1 where the map never observed the cell (empty: all observed). */
	std::vector<uint8_t> m_unknownMask;
	/** 1 on the wall cells the field measures distances to. */
	std::vector<uint8_t> m_wallMask;
	/** Accumulated segments: their lines, their extensions (with an
	 * observed map) and how many are drawn. */
	std::vector<uint8_t> m_lines, m_extension;
	std::size_t m_drawn = 0;
	/** The map last built from, its version then, and whether from its
	 * cells (buildFromSemanticMap) or as the observed area (rebuild). */
	const SemanticMap* m_source = nullptr;
	std::uint64_t m_version = 0;
	bool m_fromSemanticMap = false;
	double m_x0 = 0, m_y0 = 0, m_invRes = 20;
	int m_nx = 0, m_ny = 0;
	float m_floor = 0, m_ceiling = 0, m_unknown = 0, m_outside = 0;
};

}  // namespace semnav
