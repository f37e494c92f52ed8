/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/cascade/HaarCascade.h>

#include <string>

namespace semnav
{
/** Reads and writes HaarCascade in OpenCV's current cascade XML format (the
 * format of opencv_traincascade and of OpenCV's shipped
 * haarcascade_*.xml): `<cascade>` with stageType BOOST, featureType HAAR,
 * height/width, stageParams, featureParams, stageNum, stages (stumps as
 * `internalNodes` "0 -1 featureIdx threshold" and `leafValues` "left
 * right") and features (`rects` "x y w h weight", `tilted`), plus
 * HaarCascade::note as a string node "semnavNote" (ignored by OpenCV). What
 * is written loads in cv::CascadeClassifier; floats are written with enough
 * digits to read back bit-identical. */
class CascadeXml
{
public:
	/** The XML text. */
	static std::string toString(const HaarCascade& cascade);
	/** toString() written atomically to `path`; throws IoError. */
	static void writeFile(const std::string& path, const HaarCascade& cascade);

	/** Parses XML text; `source` names it in error messages. Throws
	 * CascadeError naming the source and what is wrong (not XML, not a
	 * BOOST/HAAR cascade, trees deeper than stumps, missing or malformed
	 * node, feature index out of range). */
	static HaarCascade fromString(
	    const std::string& xml, const std::string& source = "cascade XML");
	/** Reads a file; throws CascadeError (unreadable or invalid). */
	static HaarCascade readFile(const std::string& path);
};

}  // namespace semnav
