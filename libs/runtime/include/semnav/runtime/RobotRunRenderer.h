/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <opencv2/core/mat.hpp>
#include <string>

namespace semnav
{
class RobotSession;
class SemanticMap;

/** Picture of a semnav-robot run over its (grown) map, as semnav-nav draws
 * a simulated one: earlier plans thin orange, the last plan red, the
 * believed trajectory blue, the robot now a blue disc with its heading,
 * and a one-line summary. */
class RobotRunRenderer
{
public:
	static cv::Mat render(
	    const SemanticMap& map, const RobotSession& session,
	    int pixelsPerCell = 3);
	/** render() written as PNG, atomically; throws IoError. */
	static void write(
	    const SemanticMap& map, const RobotSession& session,
	    const std::string& path);
};

}  // namespace semnav
