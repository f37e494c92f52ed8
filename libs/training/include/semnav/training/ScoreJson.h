/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

// The scores in the apps' --json summaries (header only: the apps link
// nlohmann_json, the libraries do not).
#include <semnav/perception/GroundTruthScorer.h>
#include <semnav/training/ObjectScorer.h>

#include <nlohmann/json.hpp>

namespace semnav
{
/** {"<label>": {precision, recall, f1, pixels}} of every label seen. */
inline nlohmann::json labelScoresJson(const GroundTruthScorer& scorer)
{
	nlohmann::json j = nlohmann::json::object();
	for (Label l : scorer.labelsSeen())
	{
		const auto s = scorer.score(l);
		j[labelName(l)] = {
		    {"precision", s.precision},
		    {"recall", s.recall},
		    {"f1", s.f1},
		    {"pixels", s.groundTruthPixels}};
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
