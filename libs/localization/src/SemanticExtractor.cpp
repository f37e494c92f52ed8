/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/ClassRegistry.h>
#include <semnav/common/OptionTable.h>
#include <semnav/localization/SemanticExtractor.h>
#include <semnav/perception/LabeledSweep.h>

#include <cmath>
#include <map>
#include <set>
#include <tuple>

namespace semnav
{
namespace
{
using O = SemanticExtractor::TOptions;
const OptionTable<O>& optionTable()
{
	static const auto t =
	    OptionTable<O>()
	        .real(
	            "cell_m", &O::cell, 0.01, 5,
	            "One semantic point per label and cell of this size.")
	        .real(
	            "max_range_m", &O::maxRange, 0.5, 100,
	            "Farther labelled pixels are left out.")
	        .integer(
	            "max_samples_per_label", &O::maxSamplesPerLabel, 1, 100000,
	            "At most this many points of one label.");
	return t;
}

/** At most n of `v`, evenly spread. */
std::vector<SemanticSample> thin(std::vector<SemanticSample> v, int n)
{
	if (static_cast<int>(v.size()) <= n) return v;
	std::vector<SemanticSample> out;
	const double step = double(v.size()) / n;
	for (int i = 0; i < n; i++)
		out.push_back(v[static_cast<std::size_t>(i * step)]);
	return out;
}
}  // namespace

SEMNAV_OPTIONS_FROM_TABLE(SemanticExtractor::TOptions, optionTable())

bool SemanticExtractor::isClassLabel(Label l)
{
	return classInfo(l).hasInstances();
}

bool SemanticExtractor::isGroundLabel(Label l)
{
	return l == Label::Floor || l == Label::Sidewalk || l == Label::Grass ||
	       l == Label::Obstacle;
}

SemanticObservation SemanticExtractor::extract(const LabeledSweep& s) const
{
	SemanticObservation out;
	std::set<std::tuple<int, long, long>> cells;
	std::map<int, std::vector<SemanticSample>> byLabel;
	const double r2 = m_options.maxRange * m_options.maxRange;
	for (int r = 0; r < s.labels.rows; r++)
		for (int c = 0; c < s.labels.cols; c++)
		{
			const Label l = s.label(r, c);
			if (!isClassLabel(l) && !isGroundLabel(l)) continue;
			const auto& p = s.points.at<cv::Vec3f>(r, c);
			if (!std::isfinite(p[0]) || p[0] * p[0] + p[1] * p[1] > r2)
				continue;
			const auto key = std::make_tuple(
			    static_cast<int>(l), std::lround(p[0] / m_options.cell),
			    std::lround(p[1] / m_options.cell));
			if (cells.insert(key).second)
				byLabel[static_cast<int>(l)].push_back({p[0], p[1], l});
		}
	for (auto& [id, v] : byLabel)
	{
		auto& dst = isClassLabel(static_cast<Label>(id)) ? out.classSamples
		                                                 : out.groundSamples;
		for (const auto& x : thin(std::move(v), m_options.maxSamplesPerLabel))
			dst.push_back(x);
	}
	for (const auto& d : s.detections)
		out.objects.push_back(
		    {static_cast<float>(d.centroid.x), static_cast<float>(d.centroid.y),
		     d.label});
	return out;
}

}  // namespace semnav
