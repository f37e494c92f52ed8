/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/detection/BoxOverlap.h>
#include <semnav/training/GroundTruthObject.h>
#include <semnav/training/ObjectScorer.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>
#include <vector>

namespace semnav
{
ObjectScorer::ObjectScorer(int minPixels, double minIou)
    : m_minPixels(minPixels), m_minIou(minIou)
{
}

double ObjectScorer::iou(const cv::Rect& a, const cv::Rect& b)
{
	return boxIou(a, b);
}

ObjectScorer::ObjectKeys ObjectScorer::unrecognisable(
    const cv::Mat& groundTruth, const cv::Mat& points, double groundZ,
    const std::vector<Label>& labels) const
{
	ObjectKeys out;
	for (const auto& g : GroundTruthObject::fromLabelImage(groundTruth, labels))
	{
		if (g.pixels < m_minPixels) continue;
		const cv::Mat mask = g.mask(groundTruth);
		double sx = 0, sy = 0;
		double zMin = std::numeric_limits<double>::infinity();
		double zMax = -zMin;
		int n = 0;
		for (int r = g.box.y; r < g.box.y + g.box.height; r++)
			for (int c = g.box.x; c < g.box.x + g.box.width; c++)
			{
				const auto& p = points.at<cv::Vec3f>(r, c);
				if (!mask.at<uint8_t>(r, c) || std::isnan(p[0])) continue;
				sx += p[0];
				sy += p[1];
				zMin = std::min(zMin, double(p[2]));
				zMax = std::max(zMax, double(p[2]));
				n++;
			}
		if (n == 0) continue;
		const double bearing = std::abs(std::atan2(sy, sx)) * 180 / M_PI;
		if (bearing >= 80 || zMax - zMin < 0.5 * (zMax - groundZ))
			out.insert({g.label, g.instance});
	}
	return out;
}

std::size_t ObjectScorer::distinctCells(
    const cv::Mat& mask, const cv::Mat& points, double cellM)
{
	std::vector<std::tuple<int, int, int>> cells;
	const auto cell = [&](float v)
	{ return static_cast<int>(std::floor(v / cellM)); };
	for (int r = 0; r < mask.rows; r++)
		for (int c = 0; c < mask.cols; c++)
		{
			const auto& p = points.at<cv::Vec3f>(r, c);
			if (mask.at<uint8_t>(r, c) && !std::isnan(p[0]))
				cells.emplace_back(cell(p[0]), cell(p[1]), cell(p[2]));
		}
	std::sort(cells.begin(), cells.end());
	return static_cast<std::size_t>(
	    std::unique(cells.begin(), cells.end()) - cells.begin());
}

ObjectScorer::ObjectKeys ObjectScorer::fewDistinctPoints(
    const cv::Mat& groundTruth, const cv::Mat& points,
    const std::vector<Label>& labels, double cellM) const
{
	ObjectKeys out;
	for (const auto& g : GroundTruthObject::fromLabelImage(groundTruth, labels))
		if (g.pixels >= m_minPixels &&
		    distinctCells(g.mask(groundTruth), points, cellM) <
		        static_cast<std::size_t>(m_minPixels))
			out.insert({g.label, g.instance});
	return out;
}

void ObjectScorer::add(
    const std::vector<Detection>& detections, const cv::Mat& groundTruth,
    const std::vector<Label>& labels, const ObjectKeys& excluded)
{
	m_sweeps++;
	const auto objects = GroundTruthObject::fromLabelImage(groundTruth, labels);
	for (Label l : labels)
	{
		Score& s = m_scores[static_cast<std::size_t>(l)];
		std::vector<const GroundTruthObject*> counted, small;
		for (const auto& o : objects)
			if (o.label == l)
				(o.pixels >= m_minPixels && !excluded.count({l, o.instance})
				     ? counted
				     : small)
				    .push_back(&o);
		std::vector<const Detection*> dets;
		for (const auto& d : detections)
			if (d.label == l) dets.push_back(&d);
		std::stable_sort(
		    dets.begin(), dets.end(),
		    [](const Detection* a, const Detection* b)
		    { return a->score > b->score; });
		std::vector<bool> matched(counted.size(), false);
		for (const Detection* d : dets)
		{
			int best = -1;
			double bestIou = 0;
			for (std::size_t g = 0; g < counted.size(); g++)
			{
				if (matched[g]) continue;
				const double v = iou(d->imageBox, counted[g]->box);
				if (v >= m_minIou && v > bestIou)
				{
					bestIou = v;
					best = static_cast<int>(g);
				}
			}
			if (best >= 0)
			{
				matched[std::size_t(best)] = true;
				s.tp++;
				continue;
			}
			bool ofSmall = false;
			for (const auto* o : small)
				if (iou(d->imageBox, o->box) >= m_minIou) ofSmall = true;
			if (ofSmall)
				s.ignored++;
			else
				s.fp++;
		}
		for (bool m : matched)
			if (!m) s.fn++;
	}
}

ObjectScorer::Score ObjectScorer::score(Label l) const
{
	Score s = m_scores[static_cast<std::size_t>(l)];
	s.precision = s.tp + s.fp ? double(s.tp) / double(s.tp + s.fp) : 0.0;
	s.recall = s.tp + s.fn ? double(s.tp) / double(s.tp + s.fn) : 0.0;
	return s;
}

}  // namespace semnav
