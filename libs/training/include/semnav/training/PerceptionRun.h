/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/detection/SweepPerception.h>
#include <semnav/perception/GroundTruthScorer.h>
#include <semnav/scan/SweepAssembler.h>
#include <semnav/scan/ThreeDtkReader.h>
#include <semnav/training/ObjectScorer.h>

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace semnav
{
/** A perception run (semnav-perceive): every sweep of a rawlog, or one 3DTK
 * scan, through SweepPerception, written as images per sweep
 * (<out>/sweep_NNNN_normal.png, _segments.png, _labels.png, with objects
 * _detections.png, with ground truth _gt.png, all as seen from the robot)
 * and, with semnav-sim's ground truth, scored per label (pixels) and per
 * object class.
 *
 * A corrupt rawlog ends the run after the images of the good sweeps; run()
 * then throws RawlogError (one line, naming how many were written). */
class PerceptionRun
{
public:
	/** What a run is made of. */
	struct Settings
	{
		PerceptionPipeline::TOptions perception;
		SweepAssembler::TOptions assembler;
		ThreeDtkReader::TOptions threeDtk;
		/** Object detection; nothing: rules only. */
		std::optional<CascadeDetector::TOptions> cascades;
		/** The input: a rawlog, else one 3DTK scan. */
		std::string rawlog, scan3dtk;
		/** The output directory (created). */
		std::string out;
		/** semnav-sim's output (the directory holding <name>.labels/). */
		std::string gtDir;
	};

	/** Loads the detector and finds the ground truth; throws ConfigError,
	 * CascadeError or IoError naming the file. */
	explicit PerceptionRun(const Settings& settings);
	~PerceptionRun();

	/** Sweeps the run expects (0 when unknown). */
	std::size_t expectedSweeps() const { return m_expected; }

	/** Runs over every sweep; `progress(done)` after each. */
	void run(const std::function<void(std::size_t)>& progress = {});

	std::size_t sweeps() const { return m_done; }
	/** Whether the run was scored against ground truth. */
	bool scored() const { return !m_labelsDir.empty(); }
	bool detectsObjects() const { return m_perception.detectsObjects(); }
	/** The classes with a detector. */
	const std::vector<Label>& objectLabels() const { return m_objectLabels; }
	const GroundTruthScorer& labelScores() const { return m_scorer; }
	const ObjectScorer& objectScores() const { return m_objectScorer; }
	/** Time of the rules, and of object detection, per sweep, ms. */
	const std::vector<double>& msRules() const { return m_msRules; }
	const std::vector<double>& msDetection() const { return m_msDetection; }

	/** The ground-truth label images in `gtDir`: gtDir itself when it holds
	 * sweep_0000.png, else <stem>.labels/, else the only *.labels/. */
	static std::string findLabelsDir(
	    const std::string& gtDir, const std::string& stem);

private:
	bool nextSweep(Sweep& sweep);
	void writeImages(const Sweep& sweep, const LabeledSweep& ls);

	Settings m_settings;
	SweepPerception m_perception;
	std::vector<Label> m_objectLabels;
	std::string m_labelsDir;
	std::unique_ptr<class RawlogSweepReader> m_reader;
	std::optional<Sweep> m_single;
	std::size_t m_expected = 0, m_done = 0;
	GroundTruthScorer m_scorer;
	ObjectScorer m_objectScorer;
	std::vector<double> m_msRules, m_msDetection;
};

}  // namespace semnav
