/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/config/CConfigFile.h>
#include <semnav/common/ConfigChecks.h>
#include <semnav/detection/DetectionImage.h>
#include <semnav/detection/PanoramicProjection.h>
#include <semnav/training/CascadeTraining.h>
#include <semnav/training/SimDataset.h>

#include <chrono>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace semnav
{
namespace
{
using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t0)
{
	return std::chrono::duration<double>(Clock::now() - t0).count();
}
}  // namespace

CascadeTraining::TOptions CascadeTraining::TOptions::fromIniFile(
    const std::string& path)
{
	TOptions o;
	o.detector = CascadeDetector::TOptions::fromIniFile(path);
	std::vector<std::string> sections{
	    "CascadeDetector", "SampleGenerator", "CascadeTrainer", "NormalImage"};
	for (Label l : allLabels())
	{
		sections.push_back("CascadeDetector." + labelName(l));
		sections.push_back("CascadeTrainer." + labelName(l));
		sections.push_back("SampleGenerator." + labelName(l));
	}
	const auto cfg = openIniFile(path, sections);
	o.samples.loadFromConfigFile(*cfg, "SampleGenerator");
	for (Label l : allLabels())
		if (cfg->sectionExists("SampleGenerator." + labelName(l)))
		{
			SampleGenerator::TOptions t = o.samples;
			t.loadFromConfigFile(*cfg, "SampleGenerator." + labelName(l));
			o.samplesPerClass[l] = t;
		}
	o.trainer.loadFromConfigFile(*cfg, "CascadeTrainer");
	for (Label l : allLabels())
		if (cfg->sectionExists("CascadeTrainer." + labelName(l)))
		{
			CascadeTrainer::TOptions t = o.trainer;
			t.loadFromConfigFile(*cfg, "CascadeTrainer." + labelName(l));
			o.trainerPerClass[l] = t;
		}
	o.normals.loadFromConfigFile(*cfg, "NormalImage");
	return o;
}

IniSections CascadeTraining::TOptions::iniSections()
{
	IniSections s;
	s.add(detector, "CascadeDetector")
	    .add(samples, "SampleGenerator")
	    .add(trainer, "CascadeTrainer")
	    .add(normals, "NormalImage");
	return s;
}

CascadeTraining::CascadeTraining(const TOptions& options) : m_options(options)
{
}

std::vector<TrainingSweep> CascadeTraining::loadSweeps(
    const std::vector<std::string>& dirs, DetectionChannel channel,
    bool withRange) const
{
	std::vector<TrainingSweep> out;
	NormalImage normals(m_options.normals);
	PanoramicProjection projection;
	const auto& det = m_options.detector;
	for (const auto& dir : dirs)
		for (auto& s : SimDataset::load(dir))
		{
			normals.compute(s.sweep);
			TrainingSweep t;
			t.image = DetectionImage::fromNormals(
			    normals.normals(), normals.normalMask(), channel,
			    det.normalSmoothing, s.sweep.phis(), s.sweep.thetas());
			t.groundTruth = s.groundTruth;
			// Both layouts keep the sweep's angular steps.
			const auto& ph = s.sweep.phis();
			const auto& th = s.sweep.thetas();
			if (ph.size() > 1 && th.size() > 1)
				t.step =
				    0.5 * ((ph.back() - ph.front()) / double(ph.size() - 1) +
				           (th.back() - th.front()) / double(th.size() - 1));
			if (withRange && t.step > 0)
			{
				// Horizontal range of every pixel, as the detector's.
				const auto pts = s.sweep.points();
				t.range = cv::Mat(
				    int(s.sweep.rows()), int(s.sweep.cols()), CV_32F,
				    cv::Scalar(0));
				for (int r = 0; r < t.range.rows; r++)
					for (int c = 0; c < t.range.cols; c++)
					{
						const auto& p =
						    pts[std::size_t(r) * std::size_t(t.range.cols) +
						        std::size_t(c)];
						if (std::isfinite(p.x) && std::isfinite(p.y))
							t.range.at<float>(r, c) = std::hypot(p.x, p.y);
					}
			}
			t.elevation0 = s.sweep.thetas().front();
			t.elevation1 = s.sweep.thetas().back();
			if (det.panoramic)
			{
				// As CascadeDetector::detectionImage(); labels nearest.
				if (!projection.sameGrid(s.sweep.phis(), s.sweep.thetas()))
					projection =
					    PanoramicProjection(s.sweep.phis(), s.sweep.thetas());
				t.image = projection.toPanoramic(t.image, cv::INTER_LINEAR);
				t.groundTruth =
				    projection.toPanoramic(t.groundTruth, cv::INTER_NEAREST);
				if (!t.range.empty())
					t.range =
					    projection.toPanoramic(t.range, cv::INTER_NEAREST);
			}
			out.push_back(std::move(t));
		}
	return out;
}

std::vector<TrainingSweep> CascadeTraining::trainingSweeps(
    Label label, const std::vector<std::string>& dirs) const
{
	const auto& cls = m_options.detector.classOptions(label);
	const CascadeTrainer::TOptions& t = m_options.trainerFor(label);
	std::vector<TrainingSweep> sweeps = loadSweeps(
	    dirs, m_options.detector.channelOf(cls),
	    m_options.samplesFor(label).rangeNegatives);
	const cv::Size win(t.windowWidth, t.windowHeight);
	for (auto& s : sweeps)
	{
		s.passes = cls.passes(s.image.rows, s.elevation0, s.elevation1, win);
		if (!s.range.empty())
			s.gate = m_options.detector.rangeGate(cls, s.step, 1.0);
	}
	return sweeps;
}

std::vector<cv::Mat> CascadeTraining::positives(
    Label label, const std::vector<std::string>& dirs, uint64_t seed) const
{
	const CascadeTrainer::TOptions& t = m_options.trainerFor(label);
	return SampleGenerator(m_options.samplesFor(label))
	    .generate(
	        trainingSweeps(label, dirs), label,
	        cv::Size(t.windowWidth, t.windowHeight), seed)
	    .positives;
}

CascadeTraining::Result CascadeTraining::run(
    Label label, const std::vector<std::string>& dirs, uint64_t seed,
    const Progress& progress) const
{
	const auto& cls = m_options.detector.classOptions(label);
	const CascadeTrainer::TOptions& trainerOptions =
	    m_options.trainerFor(label);
	const std::size_t steps =
	    2 + static_cast<std::size_t>(trainerOptions.numStages);
	Result res;
	auto t0 = Clock::now();
	if (progress) progress(0, steps, "reading datasets");
	const std::vector<TrainingSweep> sweeps = trainingSweeps(label, dirs);
	res.sweeps = sweeps.size();
	res.secondsLoad = secondsSince(t0);

	t0 = Clock::now();
	if (progress) progress(1, steps, "making samples");
	const cv::Size win(trainerOptions.windowWidth, trainerOptions.windowHeight);
	SampleGenerator gen(m_options.samplesFor(label));
	auto samples = gen.generate(sweeps, label, win, seed);
	res.views = samples.views;
	res.positives = samples.positives.size();
	res.positiveSamples = samples.positives;
	res.negativeImages = samples.negatives.size();
	res.secondsSamples = secondsSince(t0);

	t0 = Clock::now();
	// Negatives are searched at the detector's scales.
	CascadeTrainer::TOptions topt = trainerOptions;
	topt.negativeScaleFactor = cls.scaleFactor;
	CascadeTrainer trainer(topt);
	res.cascade = trainer.train(
	    samples.positives, samples.negatives, seed + 1,
	    [&](std::size_t done, std::size_t, const std::string& what)
	    {
		    if (progress) progress(2 + done, steps, what);
	    });
	res.report = trainer.report();
	res.secondsTraining = secondsSince(t0);
	return res;
}

}  // namespace semnav
