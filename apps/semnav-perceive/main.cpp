/* semnav: semantic navigation from tilting-laser sweeps */
// semnav-perceive: normal image, segmentation and rule-based labels of
// every sweep of a rawlog or a 3DTK scan, optionally scored against
// semnav-sim's ground truth (docs/design.md, "Apps").
#include <mrpt/config/CConfigFile.h>
#include <semnav/common/AtomicFile.h>
#include <semnav/common/CommandLine.h>
#include <semnav/common/ConfigChecks.h>
#include <semnav/common/Error.h>
#include <semnav/common/ProgressBar.h>
#include <semnav/detection/ObjectScorer.h>
#include <semnav/detection/SweepPerception.h>
#include <semnav/perception/GroundTruthScorer.h>
#include <semnav/perception/PerceptionImages.h>
#include <semnav/perception/PerceptionPipeline.h>
#include <semnav/scan/RawlogSweepReader.h>
#include <semnav/scan/ThreeDtkReader.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace
{
std::string sweepName(std::size_t i)
{
	char buf[32];
	std::snprintf(buf, sizeof(buf), "sweep_%04zu", i);
	return buf;
}

void writePng(const std::string& path, const cv::Mat& img)
{
	std::vector<uchar> buf;
	if (!cv::imencode(".png", img, buf))
		throw semnav::IoError("cannot encode " + path);
	semnav::writeFileAtomically(path, std::string(buf.begin(), buf.end()));
}

/** The directory of ground-truth label images inside `gtDir`: gtDir itself
 * when it holds sweep_0000.png, else <stem>.labels/, else the only
 * *.labels/ directory. */
std::string findLabelsDir(const std::string& gtDir, const std::string& stem)
{
	if (!fs::is_directory(gtDir))
		throw semnav::IoError("ground-truth directory not found: " + gtDir);
	if (fs::exists(fs::path(gtDir) / "sweep_0000.png")) return gtDir;
	if (!stem.empty() && fs::is_directory(fs::path(gtDir) / (stem + ".labels")))
		return (fs::path(gtDir) / (stem + ".labels")).string();
	std::vector<fs::path> found;
	for (const auto& e : fs::directory_iterator(gtDir))
		if (e.is_directory() && e.path().extension() == ".labels")
			found.push_back(e.path());
	if (found.size() != 1)
		throw semnav::IoError(
		    "no unique <name>.labels/ directory in " + gtDir + " (found " +
		    std::to_string(found.size()) + ")");
	return found.front().string();
}

double median(std::vector<double> v)
{
	if (v.empty()) return 0;
	std::sort(v.begin(), v.end());
	const std::size_t n = v.size();
	return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/** The labels image (viewer layout) with the detection boxes. */
cv::Mat drawDetections(
    const cv::Mat& labelsViewer, cv::Size sweepSize,
    const std::vector<semnav::Detection>& dets)
{
	cv::Mat out = labelsViewer.clone();
	for (const auto& d : dets)
	{
		// Sweep layout -> viewer layout: rotated by 180 degrees.
		const cv::Rect b = d.imageBox;
		const cv::Rect v(
		    sweepSize.width - b.x - b.width, sweepSize.height - b.y - b.height,
		    b.width, b.height);
		cv::rectangle(out, v, cv::Scalar(0, 0, 0), 1);
		cv::putText(
		    out, semnav::labelName(d.label),
		    cv::Point(v.x, std::max(8, v.y - 2)), cv::FONT_HERSHEY_PLAIN, 0.7,
		    cv::Scalar(0, 0, 0));
	}
	return out;
}

struct Args
{
	std::string rawlog, tdtk, out, gtDir, config, cascades;
	bool json = false;
};

int perceive(const Args& a)
{
	semnav::PerceptionPipeline::TOptions opts;
	semnav::SweepAssembler::TOptions asmOpts;
	semnav::ThreeDtkReader::TOptions tdtkOpts;
	if (!a.config.empty())
	{
		auto sections = semnav::PerceptionPipeline::sections();
		sections.push_back("SweepAssembler");
		sections.push_back("ThreeDtkReader");
		const auto cfg = semnav::openIniFile(a.config, sections);
		opts.loadFromConfigFile(*cfg, "");
		asmOpts.loadFromConfigFile(*cfg, "SweepAssembler");
		tdtkOpts.loadFromConfigFile(*cfg, "ThreeDtkReader");
	}
	// Rules, then the Haar cascades (sec. 2.2.2) when given.
	std::optional<semnav::CascadeDetector::TOptions> cascadeOpts;
	if (!a.cascades.empty())
		cascadeOpts =
		    semnav::CascadeDetector::TOptions::fromIniFile(a.cascades);
	semnav::SweepPerception perception(opts, cascadeOpts);
	perception.pipeline().setMinLoggingLevel(mrpt::system::LVL_ERROR);
	const std::vector<semnav::Label> objectLabels = perception.objectLabels();
	semnav::ObjectScorer objectScorer;
	std::vector<double> detectionTimes;

	const std::string input = a.rawlog.empty() ? a.tdtk : a.rawlog;
	const std::string stem = fs::path(input).stem().string();
	const std::string labelsDir =
	    a.gtDir.empty() ? std::string() : findLabelsDir(a.gtDir, stem);

	// Sweep source: a rawlog read sweep by sweep, or one 3DTK scan.
	std::unique_ptr<semnav::RawlogSweepReader> reader;
	std::optional<semnav::Sweep> single;
	std::size_t total = 0;  // 0: unknown, the progress bar counts
	if (!a.rawlog.empty())
	{
		reader = std::make_unique<semnav::RawlogSweepReader>(a.rawlog, asmOpts);
		if (!labelsDir.empty())
			for (const auto& e : fs::directory_iterator(labelsDir))
				total += e.path().extension() == ".png";
	}
	else
	{
		single = semnav::ThreeDtkReader(tdtkOpts).read(a.tdtk);
		total = 1;
	}
	semnav::createDirectories(a.out);

	semnav::GroundTruthScorer scorer;
	std::vector<double> times;
	semnav::ProgressBar bar(total, "perceiving " + stem);
	semnav::LabeledSweep ls;
	semnav::Sweep sweep;
	std::size_t done = 0;
	std::string rawlogError;
	while (true)
	{
		if (reader)
		{
			bool got = false;
			try
			{
				got = reader->next(sweep);
			}
			catch (const semnav::RawlogError& e)
			{
				// The good sweeps before it are written; then one line.
				rawlogError = semnav::CommandLine::firstLine(e.what());
				break;
			}
			if (!got) break;
		}
		else
		{
			if (done > 0) break;
			sweep = *single;
		}
		perception.process(sweep, ls);
		times.push_back(perception.lastTimings().rules);
		if (perception.detectsObjects())
			detectionTimes.push_back(perception.lastTimings().detection);

		const std::string base =
		    (fs::path(a.out) / sweepName(sweep.index())).string();
		writePng(
		    base + "_normal.png",
		    semnav::perception_images::normals(
		        semnav::NormalImage::toBgr(ls.normals, ls.normalMask)));
		writePng(
		    base + "_segments.png",
		    semnav::perception_images::segments(ls.areaIds));
		const cv::Mat labelsPng =
		    semnav::perception_images::labels(ls.labels, ls.validMask);
		writePng(base + "_labels.png", labelsPng);
		if (perception.detectsObjects())
			writePng(
			    base + "_detections.png",
			    drawDetections(
			        labelsPng, cv::Size(ls.labels.cols, ls.labels.rows),
			        ls.detections));
		if (!labelsDir.empty())
		{
			const std::string gtPath =
			    (fs::path(labelsDir) / (sweepName(sweep.index()) + ".png"))
			        .string();
			if (!fs::exists(gtPath))
				throw semnav::IoError(
				    "ground truth missing for sweep " +
				    std::to_string(sweep.index()) + ": " + gtPath);
			const cv::Mat gt =
			    semnav::GroundTruthScorer::readLabelImage(gtPath);
			scorer.add(ls.labels, gt, ls.validMask);
			if (perception.detectsObjects())
			{
				// Objects need the instance ids (high byte).
				const cv::Mat gt16 = cv::imread(gtPath, cv::IMREAD_UNCHANGED);
				if (gt16.type() != CV_16UC1)
					throw semnav::IoError(
					    gtPath + " is not a 16-bit semnav-sim label image");
				objectScorer.add(ls.detections, gt16, objectLabels);
			}
			writePng(
			    base + "_gt.png",
			    semnav::perception_images::labels(gt, ls.validMask));
		}
		done++;
		bar.update(done);
	}
	bar.finish();
	if (!rawlogError.empty())
		throw semnav::RawlogError(
		    rawlogError + " (" + std::to_string(done) + " sweeps written to " +
		    a.out + ")");

	const double med = median(times);
	if (a.json)
	{
		nlohmann::json j;
		j["sweeps"] = done;
		j["ms_per_sweep_median"] = med;
		j["classes"] = nlohmann::json::object();
		if (!labelsDir.empty())
			for (const auto l : scorer.labelsSeen())
			{
				const auto s = scorer.score(l);
				j["classes"][semnav::labelName(l)] = {
				    {"precision", s.precision},
				    {"recall", s.recall},
				    {"f1", s.f1},
				    {"pixels", s.groundTruthPixels}};
			}
		// Object detection (issue 4's rule: an object counts when >= 150 of
		// its pixels are visible; IoU >= 0.3 with a not yet matched object
		// of the label is a true positive).
		j["objects"] = nlohmann::json::object();
		if (!labelsDir.empty())
			for (const auto l : objectLabels)
			{
				const auto s = objectScorer.score(l);
				j["objects"][semnav::labelName(l)] = {
				    {"tp", s.tp},         {"fp", s.fp},
				    {"fn", s.fn},         {"precision", s.precision},
				    {"recall", s.recall}, {"ignored", s.ignored}};
			}
		if (perception.detectsObjects())
			j["ms_detection_per_sweep_median"] = median(detectionTimes);
		std::cout << j.dump() << std::endl;
		return 0;
	}
	std::cout << done << " sweeps -> " << a.out << " (median " << med
	          << " ms per sweep)\n";
	if (!labelsDir.empty())
	{
		std::printf(
		    "%-12s %9s %9s %9s %10s\n", "label", "precision", "recall", "f1",
		    "gt_pixels");
		for (const auto l : scorer.labelsSeen())
		{
			const auto s = scorer.score(l);
			std::printf(
			    "%-12s %9.4f %9.4f %9.4f %10zu\n", semnav::labelName(l).c_str(),
			    s.precision, s.recall, s.f1, s.groundTruthPixels);
		}
		for (const auto l : objectLabels)
		{
			const auto s = objectScorer.score(l);
			std::printf(
			    "objects %-12s tp %zu fp %zu fn %zu precision %.3f recall "
			    "%.3f\n",
			    semnav::labelName(l).c_str(), s.tp, s.fp, s.fn, s.precision,
			    s.recall);
		}
	}
	return 0;
}
}  // namespace

int main(int argc, char** argv)
{
	semnav::CommandLine cli(
	    "semnav-perceive",
	    "Computes the normal image, the range segmentation and the rule-based "
	    "labels (floor, ceiling, wall, door, sidewalk, grass, obstacle) of "
	    "every sweep and writes <out>/sweep_NNNN_normal.png, _segments.png "
	    "and _labels.png (shown as seen from the robot: up is up, the "
	    "robot's left on the left). With --gt-dir, scores pixel "
	    "precision/recall/F1 per label (valid-range pixels) and writes the "
	    "ground truth in the same colours as _gt.png.");
	auto& cmd = cli.cmd();
	TCLAP::ValueArg<std::string> argRawlog(
	    "", "rawlog", "Input rawlog (tilting 2D laser); this or --3dtk", false,
	    "", "R", cmd);
	TCLAP::ValueArg<std::string> argTdtk(
	    "", "3dtk", "Input 3DTK scan (scanNNN.3d); this or --rawlog", false, "",
	    "F.3d", cmd);
	TCLAP::ValueArg<std::string> argOut(
	    "", "out", "Output directory (created if needed); required", false, "",
	    "DIR", cmd);
	TCLAP::ValueArg<std::string> argGt(
	    "", "gt-dir",
	    "Ground truth written by semnav-sim (the directory holding "
	    "<name>.labels/)",
	    false, "", "DIR", cmd);
	TCLAP::ValueArg<std::string> argConfig(
	    "", "config",
	    "INI file with [NormalImage] [RangeSegmentation] [Roughness] "
	    "[RuleClassifier] (and optionally [SweepAssembler] "
	    "[ThreeDtkReader]); see config/perception.ini. Default: built-in "
	    "values",
	    false, "", "C.ini", cmd);
	TCLAP::ValueArg<std::string> argCascades(
	    "", "cascades",
	    "Detect washbasins, wastebaskets and stairs with the Haar cascades "
	    "of this INI file (see config/cascade.ini); with --gt-dir the JSON "
	    "summary scores them per label (\"objects\")",
	    false, "", "C.ini", cmd);
	TCLAP::SwitchArg argJson(
	    "", "json", "Print a JSON summary on stdout", cmd, false);
	if (const auto code = cli.parse(argc, argv)) return *code;
	Args a;
	a.cascades = argCascades.getValue();
	a.rawlog = argRawlog.getValue();
	a.tdtk = argTdtk.getValue();
	a.out = argOut.getValue();
	a.gtDir = argGt.getValue();
	a.config = argConfig.getValue();
	a.json = argJson.getValue();
	if (a.rawlog.empty() == a.tdtk.empty())
		return cli.usageError("give exactly one of --rawlog and --3dtk");
	if (a.out.empty()) return cli.usageError("missing --out");
	return cli.run([&] { return perceive(a); });
}
