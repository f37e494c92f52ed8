/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/Error.h>
#include <semnav/scan/RawlogSweepReader.h>
#include <semnav/training/SimDataset.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>

namespace semnav
{
std::vector<SimSweep> SimDataset::load(const std::string& dir)
{
	namespace fs = std::filesystem;
	std::error_code ec;
	if (!fs::is_directory(dir, ec))
		throw IoError("dataset directory " + dir + " does not exist");
	std::vector<fs::path> rawlogs;
	for (const auto& e : fs::directory_iterator(dir, ec))
		if (e.path().extension() == ".rawlog") rawlogs.push_back(e.path());
	if (rawlogs.empty())
		throw IoError(
		    "dataset directory " + dir +
		    " holds no .rawlog (make one with semnav-sim)");
	std::sort(rawlogs.begin(), rawlogs.end());
	std::vector<SimSweep> out;
	for (const auto& r : rawlogs)
	{
		const fs::path labels =
		    r.parent_path() / (r.stem().string() + ".labels");
		std::vector<Sweep> sweeps = readRawlogSweeps(r.string());
		for (std::size_t i = 0; i < sweeps.size(); i++)
		{
			char name[32];
			std::snprintf(name, sizeof(name), "sweep_%04zu.png", i);
			const std::string png = (labels / name).string();
			cv::Mat gt = cv::imread(png, cv::IMREAD_UNCHANGED);
			if (gt.empty())
				throw IoError("cannot read ground-truth label image " + png);
			if (gt.type() != CV_16UC1 ||
			    gt.rows != static_cast<int>(sweeps[i].rows()) ||
			    gt.cols != static_cast<int>(sweeps[i].cols()))
				throw IoError(
				    png + " is not a 16-bit " +
				    std::to_string(sweeps[i].rows()) + " x " +
				    std::to_string(sweeps[i].cols()) + " label image");
			SimSweep s;
			s.sweep = std::move(sweeps[i]);
			s.groundTruth = gt;
			s.source = r.string() + "#" + std::to_string(i);
			out.push_back(std::move(s));
		}
	}
	return out;
}

}  // namespace semnav
