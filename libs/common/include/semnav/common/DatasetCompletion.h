/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <string>

namespace semnav
{
/** Whether a simulated dataset `<dir>/<name>.{rawlog,gt.txt,labels/}` is
 * whole: its writer calls begin() before replacing any of its files and
 * end() after the last, so that a writer killed in between leaves
 * `<dir>/<name>.incomplete`; readers that pair the files (ground-truth poses
 * or label images with a rawlog) call require(). */
class DatasetCompletion
{
public:
	/** Writes the marker (atomically, flushed to disk). */
	static void begin(const std::string& dir, const std::string& name);
	/** Removes the marker. */
	static void end(const std::string& dir, const std::string& name);
	/** Throws IoError (one line, naming the dataset and what to do) when
	 * the marker is there. */
	static void require(const std::string& dir, const std::string& name);
	static std::string markerPath(
	    const std::string& dir, const std::string& name);
};

}  // namespace semnav
