/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/AtomicFile.h>
#include <semnav/common/CommandLine.h>
#include <semnav/common/DatasetCompletion.h>
#include <semnav/common/Error.h>
#include <semnav/perception/PerceptionImages.h>
#include <semnav/scan/RawlogSweepReader.h>
#include <semnav/training/PerceptionRun.h>

#include <cstdio>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace fs = std::filesystem;

namespace semnav
{
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
	if (!cv::imencode(".png", img, buf)) throw IoError("cannot encode " + path);
	writeFileAtomically(path, std::string(buf.begin(), buf.end()));
}

/** The labels image (viewer layout) with the detection boxes. */
cv::Mat drawDetections(
    const cv::Mat& labelsViewer, cv::Size sweepSize,
    const std::vector<Detection>& dets)
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
		    out, labelName(d.label), cv::Point(v.x, std::max(8, v.y - 2)),
		    cv::FONT_HERSHEY_PLAIN, 0.7, cv::Scalar(0, 0, 0));
	}
	return out;
}
}  // namespace

namespace
{
/** The labels directory of `gtDir`, not yet checked for completeness. */
fs::path labelsDirIn(const std::string& gtDir, const std::string& stem)
{
	if (!fs::is_directory(gtDir))
		throw IoError("ground-truth directory not found: " + gtDir);
	if (fs::exists(fs::path(gtDir) / "sweep_0000.png")) return gtDir;
	if (!stem.empty() && fs::is_directory(fs::path(gtDir) / (stem + ".labels")))
		return fs::path(gtDir) / (stem + ".labels");
	std::vector<fs::path> found;
	for (const auto& e : fs::directory_iterator(gtDir))
		if (e.is_directory() && e.path().extension() == ".labels")
			found.push_back(e.path());
	if (found.size() != 1)
		throw IoError(
		    "no unique <name>.labels/ directory in " + gtDir + " (found " +
		    std::to_string(found.size()) + ")");
	return found.front();
}
}  // namespace

std::string PerceptionRun::findLabelsDir(
    const std::string& gtDir, const std::string& stem)
{
	const fs::path dir = labelsDirIn(gtDir, stem).lexically_normal();
	const fs::path named = dir.filename().empty() ? dir.parent_path() : dir;
	if (named.extension() == ".labels")
		DatasetCompletion::require(
		    named.has_parent_path() ? named.parent_path().string() : ".",
		    named.stem().string());
	return dir.string();
}

PerceptionRun::PerceptionRun(const Settings& settings)
    : m_settings(settings),
      m_perception(settings.perception, settings.cascades),
      m_objectLabels(m_perception.objectLabels())
{
	m_perception.pipeline().setMinLoggingLevel(mrpt::system::LVL_ERROR);
	const std::string input =
	    m_settings.rawlog.empty() ? m_settings.scan3dtk : m_settings.rawlog;
	if (!m_settings.gtDir.empty())
		m_labelsDir =
		    findLabelsDir(m_settings.gtDir, fs::path(input).stem().string());
	if (!m_settings.rawlog.empty())
	{
		m_reader = std::make_unique<RawlogSweepReader>(
		    m_settings.rawlog, m_settings.assembler);
		if (!m_labelsDir.empty())
			for (const auto& e : fs::directory_iterator(m_labelsDir))
				m_expected += e.path().extension() == ".png";
	}
	else
	{
		m_single =
		    ThreeDtkReader(m_settings.threeDtk).read(m_settings.scan3dtk);
		m_expected = 1;
	}
	createDirectories(m_settings.out);
}

PerceptionRun::~PerceptionRun() = default;

bool PerceptionRun::nextSweep(Sweep& sweep)
{
	if (!m_reader)
	{
		if (m_done > 0) return false;
		sweep = *m_single;
		return true;
	}
	try
	{
		return m_reader->next(sweep);
	}
	catch (const RawlogError& e)
	{
		// The good sweeps before it are written; then one line.
		throw RawlogError(
		    CommandLine::firstLine(e.what()) + " (" + std::to_string(m_done) +
		    " sweeps written to " + m_settings.out + ")");
	}
}

void PerceptionRun::writeImages(const Sweep& sweep, const LabeledSweep& ls)
{
	const std::string base =
	    (fs::path(m_settings.out) / sweepName(sweep.index())).string();
	writePng(
	    base + "_normal.png", perception_images::normals(NormalImage::toBgr(
	                              ls.normals, ls.normalMask)));
	writePng(base + "_segments.png", perception_images::segments(ls.areaIds));
	const cv::Mat labelsPng =
	    perception_images::labels(ls.labels, ls.validMask);
	writePng(base + "_labels.png", labelsPng);
	if (detectsObjects())
		writePng(
		    base + "_detections.png",
		    drawDetections(
		        labelsPng, cv::Size(ls.labels.cols, ls.labels.rows),
		        ls.detections));
	if (m_labelsDir.empty()) return;
	const std::string gtPath =
	    (fs::path(m_labelsDir) / (sweepName(sweep.index()) + ".png")).string();
	if (!fs::exists(gtPath))
		throw IoError(
		    "ground truth missing for sweep " + std::to_string(sweep.index()) +
		    ": " + gtPath);
	const cv::Mat gt = GroundTruthScorer::readLabelImage(gtPath);
	m_scorer.add(ls.labels, gt, ls.validMask);
	if (detectsObjects())
	{
		// Objects need the instance ids (high byte).
		const cv::Mat gt16 = cv::imread(gtPath, cv::IMREAD_UNCHANGED);
		if (gt16.type() != CV_16UC1)
			throw IoError(gtPath + " is not a 16-bit semnav-sim label image");
		m_objectScorer.add(ls.detections, gt16, m_objectLabels);
	}
	writePng(base + "_gt.png", perception_images::labels(gt, ls.validMask));
}

void PerceptionRun::run(const std::function<void(std::size_t)>& progress)
{
	LabeledSweep ls;
	Sweep sweep;
	while (nextSweep(sweep))
	{
		m_perception.process(sweep, ls);
		m_msRules.push_back(m_perception.lastTimings().rules);
		if (detectsObjects())
			m_msDetection.push_back(m_perception.lastTimings().detection);
		writeImages(sweep, ls);
		m_done++;
		if (progress) progress(m_done);
	}
	if (m_reader && m_done == 0) throw RawlogError(m_reader->noSweepsMessage());
}
}  // namespace semnav
