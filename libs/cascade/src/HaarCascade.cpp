/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/cascade/CascadeError.h>
#include <semnav/cascade/HaarCascade.h>

namespace semnav
{
std::size_t HaarCascade::stumpCount() const
{
	std::size_t n = 0;
	for (const auto& s : stages) n += s.stumps.size();
	return n;
}

bool HaarCascade::hasTiltedFeatures() const
{
	for (const auto& f : features)
		if (f.tilted) return true;
	return false;
}

HaarCascade HaarCascade::firstStages(std::size_t n) const
{
	HaarCascade c = *this;
	if (n < c.stages.size()) c.stages.resize(n);
	return c;
}

void HaarCascade::validate() const
{
	if (windowSize.width < 3 || windowSize.height < 3)
		throw CascadeError("cascade window must be at least 3 x 3");
	for (std::size_t i = 0; i < features.size(); i++)
		if (!features[i].fitsIn(windowSize))
			throw CascadeError(
			    "feature " + std::to_string(i) + " does not fit the " +
			    std::to_string(windowSize.width) + "x" +
			    std::to_string(windowSize.height) + " window");
	for (std::size_t s = 0; s < stages.size(); s++)
	{
		if (stages[s].stumps.empty())
			throw CascadeError(
			    "stage " + std::to_string(s) + " has no weak classifier");
		for (const auto& st : stages[s].stumps)
			if (st.featureIdx < 0 ||
			    st.featureIdx >= static_cast<int>(features.size()))
				throw CascadeError(
				    "stage " + std::to_string(s) + " uses feature " +
				    std::to_string(st.featureIdx) + " of " +
				    std::to_string(features.size()));
	}
}

bool HaarCascade::operator==(const HaarCascade& o) const
{
	if (windowSize != o.windowSize || !(features == o.features) ||
	    stages.size() != o.stages.size())
		return false;
	for (std::size_t s = 0; s < stages.size(); s++)
	{
		const auto &a = stages[s], &b = o.stages[s];
		if (a.threshold != b.threshold || a.stumps.size() != b.stumps.size())
			return false;
		for (std::size_t i = 0; i < a.stumps.size(); i++)
		{
			const auto &x = a.stumps[i], &y = b.stumps[i];
			if (x.featureIdx != y.featureIdx || x.threshold != y.threshold ||
			    x.left != y.left || x.right != y.right)
				return false;
		}
	}
	return true;
}

}  // namespace semnav
