/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/config/CConfigFile.h>
#include <semnav/common/ConfigChecks.h>
#include <semnav/detection/CascadeTraining.h>
#include <semnav/detection/DetectionImage.h>
#include <semnav/detection/PanoramicProjection.h>
#include <semnav/detection/SimDataset.h>

#include <chrono>
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
	}
	const auto cfg = openIniFile(path, sections);
	o.samples.loadFromConfigFile(*cfg, "SampleGenerator");
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

CascadeTraining::CascadeTraining(const TOptions& options) : m_options(options)
{
}

std::vector<TrainingSweep> CascadeTraining::loadSweeps(
    const std::vector<std::string>& dirs, DetectionChannel channel) const
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
			}
			out.push_back(std::move(t));
		}
	return out;
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
	std::vector<TrainingSweep> sweeps =
	    loadSweeps(dirs, m_options.detector.channelOf(cls));
	res.sweeps = sweeps.size();
	res.secondsLoad = secondsSince(t0);

	t0 = Clock::now();
	if (progress) progress(1, steps, "making samples");
	const cv::Size win(trainerOptions.windowWidth, trainerOptions.windowHeight);
	for (auto& s : sweeps)
		s.passes = cls.passes(s.image.rows, s.elevation0, s.elevation1, win);
	SampleGenerator gen(m_options.samples);
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
