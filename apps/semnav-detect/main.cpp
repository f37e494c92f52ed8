/* semnav: semantic navigation from tilting-laser sweeps */
// semnav-detect: runs perception and the Haar cascade detector on simulated
// datasets and scores the detections against the ground truth (object
// precision / recall per class, issue 4's rule).
#include <semnav/common/AtomicFile.h>
#include <semnav/common/CommandLine.h>
#include <semnav/common/DatasetListArg.h>
#include <semnav/common/Percentile.h>
#include <semnav/common/ProgressBar.h>
#include <semnav/detection/CascadeDetector.h>
#include <semnav/detection/DetectionImage.h>
#include <semnav/perception/PerceptionPipeline.h>
#include <semnav/training/CascadeConfigArg.h>
#include <semnav/training/CascadeTraining.h>
#include <semnav/training/DetectionEvaluation.h>
#include <semnav/training/GroundTruthObject.h>
#include <semnav/training/ObjectScorer.h>
#include <semnav/training/ScoreJson.h>
#include <semnav/training/SimDataset.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <utility>
#include <vector>

namespace
{
using Evaluation = semnav::DetectionEvaluation;
constexpr int kCountedPixels = Evaluation::kCountedPixels;
constexpr double kMatchIou = Evaluation::kMatchIou;
constexpr double kCellM = Evaluation::kCellM;

/** Detection image with the object proposals of every class (yellow), ground
 * truth (blue), accepted (green) and rejected (red) boxes, enlarged 2x; sweep
 * layout flipped to the viewer's (up is up). */
cv::Mat drawSweep(
    const cv::Mat& image, const std::vector<semnav::GroundTruthObject>& gt,
    const std::vector<semnav::CascadeDetector::Candidate>& cands,
    const std::vector<std::vector<semnav::ObjectProposal>>& proposals)
{
	cv::Mat bgr;
	cv::cvtColor(image, bgr, cv::COLOR_GRAY2BGR);
	cv::resize(bgr, bgr, cv::Size(), 2, 2, cv::INTER_NEAREST);
	const auto box = [](cv::Rect r)
	{ return cv::Rect(r.x * 2, r.y * 2, r.width * 2, r.height * 2); };
	for (const auto& ps : proposals)
		for (const auto& p : ps)
			cv::rectangle(bgr, box(p.box), cv::Scalar(0, 220, 255), 1);
	for (const auto& g : gt)
		cv::rectangle(
		    bgr, box(g.box),
		    g.pixels >= kCountedPixels ? cv::Scalar(255, 0, 0)
		                               : cv::Scalar(255, 180, 0),
		    1);
	for (const auto& c : cands)
		cv::rectangle(
		    bgr, box(c.box),
		    c.accepted ? cv::Scalar(0, 255, 0) : cv::Scalar(0, 0, 255), 1);
	cv::Mat out;
	cv::rotate(bgr, out, cv::ROTATE_180);
	for (const auto& c : cands)
	{
		const cv::Rect b = box(c.box);
		const cv::Point at(
		    out.cols - b.x - b.width, out.rows - b.y - b.height - 2);
		std::string t = semnav::labelName(c.label).substr(0, 5);
		if (!c.accepted) t += " " + c.rejection;
		cv::putText(
		    out, t, at, cv::FONT_HERSHEY_PLAIN, 0.8,
		    c.accepted ? cv::Scalar(0, 255, 0) : cv::Scalar(0, 0, 255));
	}
	return out;
}

/** Which ground-truth objects `pixels` lie on: the two largest shares,
 * e.g. "62 % washbasin #6, 30 % wall #2". */
std::string pointsOn(
    const cv::Mat& groundTruth, const std::vector<cv::Point>& pixels)
{
	std::map<uint16_t, std::size_t> on;
	for (const auto& p : pixels) on[groundTruth.at<uint16_t>(p)]++;
	std::vector<std::pair<std::size_t, uint16_t>> shares;
	for (const auto& [code, n] : on) shares.emplace_back(n, code);
	std::sort(shares.rbegin(), shares.rend());
	std::string out;
	for (std::size_t i = 0; i < std::min<std::size_t>(2, shares.size()); i++)
	{
		const auto [n, code] = shares[i];
		char buf[80];
		std::snprintf(
		    buf, sizeof(buf), "%s%.0f %% %s #%d", i ? ", " : "",
		    100.0 * double(n) / double(pixels.size()),
		    semnav::labelName(semnav::labelFromId(unsigned(code & 0xff)))
		        .c_str(),
		    code >> 8);
		out += buf;
	}
	return out.empty() ? "no points" : out;
}

/** One stderr line per counted object without a matching accepted
 * detection: its box, pixels, range and bearing, and the candidate of its
 * label that overlaps it most (IoU of the measured box, fate). */
void listMisses(
    const std::string& dir, std::size_t sweep, const cv::Mat& groundTruth,
    const cv::Mat& points, const cv::Mat& objectMask,
    const std::vector<semnav::GroundTruthObject>& objects,
    const std::vector<semnav::CascadeDetector::Candidate>& cands)
{
	for (const auto& c : cands)
	{
		if (!c.accepted) continue;
		bool matches = false;
		for (const auto& g : objects)
			matches |=
			    g.label == c.label &&
			    semnav::ObjectScorer::iou(c.measure->box, g.box) >= kMatchIou;
		if (matches) continue;
		const auto& m = *c.measure;
		std::fprintf(
		    stderr,
		    "false %s sweep %zu %s box %dx%d+%d+%d, range %.2f m, bearing "
		    "%.0f deg, width %.2f m, top %.2f m, %zu points, shape score "
		    "%.2f, flat faces %.2f, on %s\n",
		    std::filesystem::path(dir).filename().c_str(), sweep,
		    semnav::labelName(c.label).c_str(), m.box.width, m.box.height,
		    m.box.x, m.box.y, std::hypot(m.centroid.x, m.centroid.y),
		    std::atan2(m.centroid.y, m.centroid.x) * 180 / M_PI, m.width, m.top,
		    m.points, c.shapeScore, c.flatFaceShare.value_or(-1),
		    pointsOn(groundTruth, m.pixels).c_str());
	}
	for (const auto& g : objects)
	{
		if (g.pixels < kCountedPixels) continue;
		double bestAccepted = 0, best = 0, bestOnIt = 0;
		const semnav::CascadeDetector::Candidate *nearest = nullptr,
		                                         *onIt = nullptr;
		for (const auto& c : cands)
		{
			if (c.label != g.label || !c.measure) continue;
			const double v = semnav::ObjectScorer::iou(c.measure->box, g.box);
			if (c.accepted) bestAccepted = std::max(bestAccepted, v);
			if (v > best)
			{
				best = v;
				nearest = &c;
			}
			if (v > bestOnIt && g.shareOf(groundTruth, c.measure->pixels) > 0.5)
			{
				bestOnIt = v;
				onIt = &c;
			}
		}
		if (bestAccepted >= kMatchIou) continue;
		const auto fate = [&](const semnav::CascadeDetector::Candidate* c)
		{
			if (!c) return std::string("(no measured candidate)");
			char buf[320];
			std::snprintf(
			    buf, sizeof(buf),
			    "(%s%s; %s, width %.2f m, top %.2f m, %zu points, %s; on %s)",
			    c->accepted ? "accepted" : "rejected: ",
			    c->accepted ? "" : c->rejection.c_str(),
			    c->fromSegment ? "segment" : "cascade box", c->measure->width,
			    c->measure->top, c->measure->points,
			    c->shape ? ("shape score " +
			                std::to_string(c->shapeScore).substr(0, 4))
			                   .c_str()
			             : "no shape check",
			    pointsOn(groundTruth, c->measure->pixels).c_str());
			return std::string(buf);
		};
		const cv::Mat mask = g.mask(groundTruth);
		cv::Vec3d sum(0, 0, 0);
		int n = 0, inProposals = 0;
		for (int r = 0; r < mask.rows; r++)
			for (int c = 0; c < mask.cols; c++)
			{
				const auto& p = points.at<cv::Vec3f>(r, c);
				if (!mask.at<uint8_t>(r, c) || std::isnan(p[0])) continue;
				sum += cv::Vec3d(p[0], p[1], p[2]);
				n++;
				inProposals += objectMask.at<uint8_t>(r, c) != 0;
			}
		// Beside the robot its pixels repeat a few points.
		const std::size_t distinct =
		    semnav::ObjectScorer::distinctCells(mask, points, kCellM);
		const cv::Vec3d m = n ? sum / n : sum;
		std::fprintf(
		    stderr,
		    "miss %s sweep %zu %s #%d box %dx%d+%d+%d %d px (%zu distinct 2 cm "
		    "cells), range %.2f m, bearing %.0f deg, height %.2f m, %.0f %% in "
		    "the proposal mask; "
		    "nearest candidate IoU %.2f %s; of those mostly on it, IoU %.2f "
		    "%s\n",
		    std::filesystem::path(dir).filename().c_str(), sweep,
		    semnav::labelName(g.label).c_str(), g.instance, g.box.width,
		    g.box.height, g.box.x, g.box.y, g.pixels, distinct,
		    std::hypot(m[0], m[1]), std::atan2(m[1], m[0]) * 180 / M_PI, m[2],
		    n ? 100.0 * inProposals / n : 0.0, best, fate(nearest).c_str(),
		    bestOnIt, fate(onIt).c_str());
	}
}
nlohmann::json otherCountJson(const Evaluation::OtherCount& o, semnav::Label l)
{
	const auto s = o.scorer.score(l);
	const auto e = o.excluded.find(l);
	return {
	    {"tp", s.tp},
	    {"fp", s.fp},
	    {"fn", s.fn},
	    {"excluded", e == o.excluded.end() ? 0 : e->second},
	    {"precision", s.precision},
	    {"recall", s.recall}};
}

void printOtherCount(
    const Evaluation::OtherCount& o, const std::vector<semnav::Label>& labels)
{
	std::printf("%s:\n", o.title.c_str());
	for (auto l : labels)
	{
		const auto s = o.scorer.score(l);
		const auto e = o.excluded.find(l);
		std::printf(
		    "  %-12s tp %4zu  fp %4zu  fn %4zu  (excluded %zu)  precision "
		    "%.3f  recall %.3f\n",
		    semnav::labelName(l).c_str(), s.tp, s.fp, s.fn,
		    e == o.excluded.end() ? 0 : e->second, s.precision, s.recall);
	}
}
Evaluation::Funnel funnelOf(const Evaluation& ev, semnav::Label l)
{
	const auto it = ev.funnels().find(l);
	return it == ev.funnels().end() ? Evaluation::Funnel() : it->second;
}

nlohmann::json summaryJson(const Evaluation& ev)
{
	nlohmann::json j, objs, objsRecognisable, objsDistinct;
	for (auto l : ev.labels())
	{
		const std::string name = semnav::labelName(l);
		objs[name] = semnav::objectScoreJson(ev.scorer().score(l));
		objsRecognisable[name] = otherCountJson(ev.recognisable(), l);
		objsDistinct[name] = otherCountJson(ev.distinct(), l);
		const auto f = funnelOf(ev, l);
		j["funnel"][name] = {
		    {"counted", f.counted},
		    {"reached", f.reached},
		    {"sized", f.sized},
		    {"accepted", f.accepted}};
	}
	j["objects"] = objs;
	j["objects_recognisable"] = objsRecognisable;
	nlohmann::json views = nlohmann::json::object();
	for (const auto& [id, n] : ev.recognisableViews())
		views[std::to_string(id)] = n;
	j["recognisable_views"] = views;
	j["objects_distinct_points"] = objsDistinct;
	j["sweeps"] = ev.scorer().sweeps();
	j["ms_per_sweep_median"] = semnav::median(ev.msTotal());
	j["ms_cascades_median"] = semnav::median(ev.msCascades());
	j["rejected"] = ev.rejections();
	return j;
}

void printSummary(const Evaluation& ev)
{
	const auto& labels = ev.labels();
	for (auto l : labels)
	{
		const auto s = ev.scorer().score(l);
		std::printf(
		    "%-12s tp %4zu  fp %4zu  fn %4zu  (ignored %zu)  precision %.3f  "
		    "recall %.3f\n",
		    semnav::labelName(l).c_str(), s.tp, s.fp, s.fn, s.ignored,
		    s.precision, s.recall);
	}
	printOtherCount(ev.recognisable(), labels);
	printOtherCount(ev.distinct(), labels);
	std::printf(
	    "counted objects a candidate reaches (IoU >= 0.3), of them past the "
	    "size check, an accepted one reaches:\n");
	for (auto l : labels)
	{
		const auto f = funnelOf(ev, l);
		const auto share = [&](std::size_t k)
		{ return f.counted ? double(k) / double(f.counted) : 0.0; };
		std::printf(
		    "  %-12s %4zu counted  %4zu reached (%.3f)  %4zu sized (%.3f)  "
		    "%4zu accepted (%.3f)\n",
		    semnav::labelName(l).c_str(), f.counted, f.reached,
		    share(f.reached), f.sized, share(f.sized), f.accepted,
		    share(f.accepted));
	}
	std::printf(
	    "%zu sweeps, detection %.2f ms per sweep (median; cascades %.2f ms)\n",
	    ev.scorer().sweeps(), semnav::median(ev.msTotal()),
	    semnav::median(ev.msCascades()));
	for (const auto& kv : ev.rejections())
		std::printf(
		    "  rejected by size check: %s x %zu\n", kv.first.c_str(),
		    kv.second);
}
}  // namespace

int main(int argc, char** argv)
{
	semnav::CommandLine cli(
	    "semnav-detect",
	    "Runs perception and the cascade detector (washbasin, wastebasket, "
	    "stairs) on datasets written by semnav-sim and scores the "
	    "detections: a ground-truth object counts when >= 150 of its pixels "
	    "are visible; a detection is a true positive when its box has IoU >= "
	    "0.3 with a not yet matched object of its label.");
	auto& cmd = cli.cmd();
	semnav::DatasetListArg argDatasets(
	    cmd, "Dataset directories (semnav-sim output); required");
	const semnav::CascadeConfigArg argConfig(cli, true);
	TCLAP::ValueArg<std::string> argOut(
	    "", "out", "Write one PNG per sweep with the boxes here", false, "",
	    "DIR", cmd);
	TCLAP::SwitchArg& argJson = cli.addJson();
	TCLAP::SwitchArg argMisses(
	    "", "misses",
	    "List on stderr every accepted detection that matches no object and "
	    "every counted object no accepted detection matches (where it is, "
	    "and the nearest candidate's IoU and fate)",
	    cmd, false);
	if (const auto code = cli.parse(argc, argv)) return *code;
	const std::vector<std::string> datasets = argDatasets.values();
	if (datasets.empty()) return cli.usageError("missing --datasets");

	return cli.run(
	    [&]
	    {
		    const auto opts = semnav::CascadeDetector::TOptions::fromIniFile(
		        argConfig.path());
		    Evaluation ev(opts);
		    auto& detector = ev.detector();
		    const auto& labels = ev.labels();
		    if (!argOut.getValue().empty())
			    semnav::createDirectories(argOut.getValue());
		    std::size_t n = 0;
		    for (const auto& dir : datasets)
		    {
			    const auto sweeps = semnav::SimDataset::load(dir);
			    semnav::ProgressBar bar(sweeps.size(), "detecting in " + dir);
			    for (std::size_t i = 0; i < sweeps.size(); i++, n++)
			    {
				    const auto r = ev.add(sweeps[i]);
				    const auto& ls = r.perception;
				    const auto& sw = sweeps[i].sweep;
				    const auto& cands = r.candidates;
				    if (argMisses.getValue())
				    {
					    listMisses(
					        dir, i, sweeps[i].groundTruth, ls.points,
					        semnav::ObjectProposals::objectMask(
					            ls.points, ls.labels, ls.areaIds, ls.groundZ,
					            opts.proposalParams(
					                opts.proposalJoinPx,
					                opts.proposalRangeGap)),
					        r.objects, cands);
				    }
				    if (!argOut.getValue().empty())
				    {
					    const cv::Mat img = detector.detectionImage(
					        sw.phis(), sw.thetas(), ls.normals, ls.normalMask);
					    const cv::Mat gtImage =
					        opts.panoramic
					            ? detector.projection().toPanoramic(
					                  sweeps[i].groundTruth, cv::INTER_NEAREST)
					            : sweeps[i].groundTruth;
					    const auto gt =
					        semnav::GroundTruthObject::fromLabelImage(
					            gtImage, labels);
					    char name[64];
					    std::snprintf(
					        name, sizeof(name), "/%03zu_%s_%02zu.png", n,
					        std::filesystem::path(dir).filename().c_str(), i);
					    cv::imwrite(
					        argOut.getValue() + name,
					        drawSweep(
					            img, gt, cands, detector.lastProposals()));
				    }
				    bar.update(i + 1);
			    }
		    }
		    if (argJson.getValue())
			    std::cout << summaryJson(ev).dump() << std::endl;
		    else
			    printSummary(ev);
		    return 0;
	    });
}
