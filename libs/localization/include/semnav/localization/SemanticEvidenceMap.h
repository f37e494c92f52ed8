/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/math/TPoint2D.h>
#include <semnav/common/CellRect.h>
#include <semnav/common/GridGeometry.h>
#include <semnav/common/Label.h>
#include <semnav/localization/SemanticObservation.h>

#include <array>
#include <cstdint>
#include <vector>

namespace semnav
{
class SemanticMap;
class ObjectFootprints;

/** The semantic side of the localization likelihood: how well a sweep's
 * labels and objects (SemanticObservation) agree with a known semantic map
 * where a particle puts them. Beside the wall landmarks, this is what tells
 * a room from its mirror image when a door, a washbasin or a wastebasket
 * stands on one side of it.
 *
 * - Class points (door, stairs, washbasin, wastebasket) and ground points
 *   (floor, sidewalk, grass, obstacle): a likelihood field per label from
 *   the map's "labels" layer, as the wall map's (Gaussian in the distance
 *   to the nearest cell of that label, plus a random part; cells the map
 *   never observed score unknown_weight).
 * - Objects: each detection's centroid against the nearest map instance of
 *   its label (Gaussian in the distance, plus a random part).
 * Each term is the mean log-likelihood of its points times its weight in
 * effective points (class_points, ground_points, object_points; 0 turns it
 * off). Labels the map does not hold are not scored (every pose alike).
 *
 * Options: INI section [SemanticEvidence] (config/localization.ini). */
class SemanticEvidenceMap
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

		/** class_points, ground_points, object_points: weight of each term
		 * in effective independent points (0: off). */
		double classPoints = 6;
		double groundPoints = 3;
		double objectPoints = 6;
		/** sigma_m, max_distance_m: class and ground points. */
		double sigma = 0.15;
		double maxDistance = 1.0;
		/** object_sigma_m, object_max_distance_m: detections. */
		double objectSigma = 0.3;
		double objectMaxDistance = 2.0;
		/** hit_weight, random_weight: mixture of the Gaussian and a
		 * uniform part. */
		double hitWeight = 0.9;
		double randomWeight = 0.1;
		/** unknown_weight: likelihood of a point in a never-observed
		 * cell. */
		double unknownWeight = 0.3;
		/** mapping_flat_labels_only: while mapping (observedPart), only
		 * the flat ground labels (floor, sidewalk, grass) are scored. The
		 * points of an obstacle, a door or a bin lie on the faces the
		 * sweep sees; the map so far holds the faces seen from earlier
		 * poses, so matching them pulls each estimate back toward those
		 * poses (by up to the object's depth), sweep after sweep. */
		bool mappingFlatLabelsOnly = true;

		bool enabled() const
		{
			return classPoints > 0 || groundPoints > 0 || objectPoints > 0;
		}
	};

	SemanticEvidenceMap() = default;
	explicit SemanticEvidenceMap(const TOptions& o) : m_options(o) {}

	/** Fields and object instances of a known map; `flatOnly`: the fields
	 * of the flat labels only (what mapping scores, see observedPart). */
	void build(const SemanticMap& map, bool flatOnly = false);
	/** The same for `map` grown since the last build() or update() from
	 * it: only the cells near those whose labels or observed state changed
	 * (SemanticMap::changesSince) are recomputed, with the result of
	 * build(). A grown grid, another map or other labels build anew. */
	void update(const SemanticMap& map, bool flatOnly = false);
	bool empty() const { return m_geometry.cellCount() == 0; }

	/** Log-likelihood of the observation seen from (x, y, yaw): the
	 * weighted sum of the three terms. */
	double logLikelihood(
	    double x, double y, double yaw, const SemanticObservation& obs) const;
	/** The terms alone (each already weighted). */
	struct Terms
	{
		double classes = 0, ground = 0, objects = 0, footprints = 0;
		double total() const { return classes + ground + objects + footprints; }
	};
	Terms terms(
	    double x, double y, double yaw, const SemanticObservation& obs) const;
	/** The same, class and ground points counted only where the map
	 * observed the cell (what the map cannot tell is left out). */
	Terms knownTerms(
	    double x, double y, double yaw, const SemanticObservation& obs) const;

	/** The part of the observation the map can judge when seen from
	 * (x, y, yaw): class and ground points in cells the map observed and
	 * holding a field of their label, detections of labels with
	 * instances; with `mapping_flat_labels_only`, only floor, sidewalk
	 * and grass points. Mapping scores this fixed subset at every
	 * particle, so that no particle gains by pushing points into unseen
	 * cells (nor loses: the frontier bias). */
	SemanticObservation observedPart(
	    double x, double y, double yaw, const SemanticObservation& obs) const;

	/** Mapping: the landmarks the observation's footprints are scored
	 * against (owned by the caller; nullptr: none). */
	void setFootprints(const ObjectFootprints* f) { m_footprints = f; }

	/** True when the map has cells of label l. */
	bool hasField(Label l) const
	{
		return !m_fields[static_cast<std::size_t>(l)].empty();
	}
	const TOptions& options() const { return m_options; }
	/** The likelihood field of label l, per cell (empty: not scored). */
	const std::vector<float>& field(Label l) const
	{
		return m_fields[static_cast<std::size_t>(l)];
	}

private:
	/** True when label l gets a field (with `flatOnly`: flat labels only). */
	static bool scored(Label l, bool flatOnly);
	/** Recomputes the field of label l over `cells` (clipped) and the cells
	 * within max_distance_m of them, from the map's labels. */
	void computeField(
	    Label l, const std::vector<float>& labels, const CellRect& cells);
	/** The objects: the map's reported instances. */
	void takeObjects(const SemanticMap& map);
	double meanField(
	    double x, double y, double c, double s,
	    const std::vector<SemanticSample>& pts, bool knownOnly) const;
	Terms termsOf(
	    double x, double y, double yaw, const SemanticObservation& obs,
	    bool knownOnly) const;
	double meanObjects(
	    double x, double y, double c, double s,
	    const std::vector<SemanticSample>& objects) const;
	float value(double d, double sigma, double maxDistance) const;

	TOptions m_options;
	GridGeometry m_geometry;
	std::array<std::vector<float>, kMaxLabelCount> m_fields;
	std::array<std::vector<mrpt::math::TPoint2D>, kMaxLabelCount> m_objects;
	float m_outside = 0;
	/** 1 where the map never observed the cell. */
	std::vector<uint8_t> m_unknown;
	const ObjectFootprints* m_footprints = nullptr;
	/** What update() compares against: the map built from, its version
	 * and labels layer then, and the labels present. */
	const SemanticMap* m_source = nullptr;
	std::uint64_t m_version = 0;
	bool m_flatOnly = false;
	std::vector<float> m_labels;
	uint32_t m_present = 0;
};

}  // namespace semnav
