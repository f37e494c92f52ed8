/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/scan/Sweep.h>

#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

namespace semnav
{
/** A simulated sweep with its ground-truth label image. */
struct SimSweep
{
	Sweep sweep;
	/** CV_16U, sweep layout: low byte = label id, high byte = instance id
	 * (semnav-sim's `<name>.labels/sweep_NNNN.png`). */
	cv::Mat groundTruth;
	/** "<dir>/<name>.rawlog#<index>", for messages. */
	std::string source;
};

/** Reads what semnav-sim wrote in a directory. */
class SimDataset
{
public:
	/** Every `<name>.rawlog` in `dir` (sorted by name) with the label
	 * image of each sweep. Throws IoError when the directory has no rawlog
	 * or a label image is missing or has the wrong size, RawlogError for a
	 * corrupt rawlog. */
	static std::vector<SimSweep> load(const std::string& dir);
};

}  // namespace semnav
