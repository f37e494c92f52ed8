/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once
// The office dataset simulated (seed 1), read back and perceived once, with
// the true pose of every sweep: the input of the map and localization
// benchmarks.
#include <mrpt/poses/CPose2D.h>
#include <semnav/perception/LabeledSweep.h>
#include <semnav/perception/PerceptionPipeline.h>
#include <semnav/scan/GroundTruthLog.h>
#include <semnav/scan/RawlogSweepReader.h>
#include <semnav/sim/SceneLoader.h>
#include <semnav/sim/SimulationRunner.h>

#include <filesystem>
#include <string>
#include <vector>

namespace semnav::test
{
struct PerceivedRun
{
	std::vector<Sweep> sweeps;
	std::vector<LabeledSweep> labeled;
	std::vector<mrpt::poses::CPose2D> truePoses;
};

/** Simulates datasets/office into a temporary directory named `tmpName`
 * and perceives every sweep. */
inline PerceivedRun perceivedOffice(const std::string& tmpName)
{
	PerceivedRun out;
	const Scene scene = SceneLoader::loadFile(
	    std::string(SEMNAV_SOURCE_DIR) + "/datasets/office/office.yaml");
	const auto dir = std::filesystem::temp_directory_path() / tmpName;
	const auto res = SimulationRunner(scene, SimulationRunner::TOptions(), 1)
	                     .run(dir.string());
	const GroundTruthLog gt(dir.string(), scene.name);
	PerceptionPipeline p;
	out.sweeps = readRawlogSweeps(res.rawlogPath);
	for (const auto& s : out.sweeps)
	{
		out.labeled.push_back(p.process(s));
		out.truePoses.push_back(gt.pose(s.index()));
	}
	return out;
}

}  // namespace semnav::test
