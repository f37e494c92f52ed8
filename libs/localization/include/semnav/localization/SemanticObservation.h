/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/common/Label.h>

#include <vector>

namespace semnav
{
/** A labelled point on the floor plane, robot frame (m). */
struct SemanticSample
{
	float x = 0, y = 0;
	Label label = Label::Unknown;
};

/** What one sweep says besides its walls, in the robot frame: labelled
 * points (thinned; grouped by label) and the centroids of the objects the
 * detectors found. The particle filter scores them against the map's label
 * layer and object instances (SemanticEvidenceMap). */
struct SemanticObservation
{
	/** Class points (door, stairs, washbasin, wastebasket, ...) and ground
	 * points (floor, sidewalk, grass, obstacle). */
	std::vector<SemanticSample> classSamples, groundSamples;
	/** Detected objects (centroid, label). */
	std::vector<SemanticSample> objects;
	/** Mapping: object footprints (centres of posts, bins; see
	 * ObjectFootprints). */
	std::vector<SemanticSample> footprints;
	bool empty() const
	{
		return classSamples.empty() && groundSamples.empty() &&
		       objects.empty() && footprints.empty();
	}
};

}  // namespace semnav
