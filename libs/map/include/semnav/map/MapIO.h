/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/map/SemanticMap.h>

#include <string>

namespace semnav
{
/** Reads and writes the map directory of docs/design.md.
 *
 * `map.yaml` has the ROS map_server keys (image, resolution, origin,
 * occupied_thresh, free_thresh, negate) plus a `semnav:` section with the
 * layer files, the object list and the number of sweeps. The objects are
 * those the map reports (SemanticMap::instances()): candidates (seen too
 * seldom, implausible size) are neither listed nor kept in the objects
 * layers, so map.yaml, summaries and goals agree. Images have
 * map_server's orientation (row 0 = the largest y). Files:
 * occupancy.png (map_server trinary: 0 occupied, 254 free, 205 unknown,
 * otherwise 255 (1 - p)), labels.png (16-bit LabelSet mask:
 * classes with ids 16..23 are in layers/labels.pfm only), objects.png
 * (16-bit instance id), cost.png (16-bit, u / L * 65535), map.png (colour
 * rendering), octomap.bt, and under layers/ the exact state (log-odds
 * occupancy and every float layer as PFM) so that load(save(m)) == m.
 * The directory is replaced as a whole (StagedDirectory; docs/design.md,
 * "Map directory"): a kill leaves the complete old or new map, and a load
 * concurrent with a save reads one of them. */
class MapIO
{
public:
	/** Throws IoError when `dir` holds anything but a map's files (save()
	 * would refuse to replace it). */
	static void save(const SemanticMap& map, const std::string& dir);
	/** What save() would refuse, checked before long work. */
	static void checkTarget(const std::string& dir);
	/** Loads into `map` (whose options are kept); throws IoError naming the
	 * file (and the line for map.yaml) on anything missing or corrupt. */
	static void load(const std::string& dir, SemanticMap& map);
};

}  // namespace semnav
