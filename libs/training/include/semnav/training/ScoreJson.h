/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

// The scores in the apps' --json summaries (header only: the apps link
// nlohmann_json, the libraries do not).
#include <semnav/perception/GroundTruthScorer.h>
#include <semnav/training/ObjectScorer.h>

#include <nlohmann/json.hpp>

namespace semnav
{
/** {"<label>": {precision, recall, f1, pixels, predicted_as}} of every
 * label seen; predicted_as: {"<label>" or "unknown": ground-truth pixels of
 * this label predicted so} for the other labels with any. */
inline nlohmann::json labelScoresJson(const GroundTruthScorer& scorer)
{
	nlohmann::json j = nlohmann::json::object();
	for (Label l : scorer.labelsSeen())
	{
		const auto s = scorer.score(l);
		nlohmann::json as = nlohmann::json::object();
		for (std::size_t k = 0; k < allLabels().size(); k++)
		{
			const auto p = static_cast<Label>(k);
			const std::size_t n = scorer.confusion(l, p);
			if (p != l && n > 0)
				as[p == Label::Unknown ? "unknown" : labelName(p)] = n;
		}
		j[labelName(l)] = {
		    {"precision", s.precision},
		    {"recall", s.recall},
		    {"f1", s.f1},
		    {"pixels", s.groundTruthPixels},
		    {"predicted_as", as}};
	}
	return j;
}

/** {tp, fp, fn, ignored, precision, recall} of one class. */
inline nlohmann::json objectScoreJson(const ObjectScorer::Score& s)
{
	return {
	    {"tp", s.tp},
	    {"fp", s.fp},
	    {"fn", s.fn},
	    {"ignored", s.ignored},
	    {"precision", s.precision},
	    {"recall", s.recall}};
}

}  // namespace semnav
