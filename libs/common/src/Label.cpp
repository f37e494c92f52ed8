/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/Error.h>
#include <semnav/common/Label.h>
#include <semnav/common/LabelSet.h>

namespace semnav
{
namespace
{
const std::array<std::string, kLabelCount> kNames = {
    "unknown", "floor",  "ceiling",   "wall",        "door",    "sidewalk",
    "grass",   "stairs", "washbasin", "wastebasket", "obstacle"};
}

const std::array<Label, kLabelCount>& allLabels()
{
	static const std::array<Label, kLabelCount> all = []
	{
		std::array<Label, kLabelCount> a{};
		for (std::size_t i = 0; i < kLabelCount; i++)
			a[i] = static_cast<Label>(i);
		return a;
	}();
	return all;
}

const std::string& labelName(Label l)
{
	const auto i = static_cast<std::size_t>(l);
	if (i >= kLabelCount) return kNames[0];
	return kNames[i];
}

std::string knownLabelNames()
{
	std::string s;
	for (const auto& n : kNames)
	{
		if (!s.empty()) s += ", ";
		s += n;
	}
	return s;
}

Label labelFromName(const std::string& name)
{
	for (std::size_t i = 0; i < kLabelCount; i++)
		if (kNames[i] == name) return static_cast<Label>(i);
	throw UnknownLabelError(
	    "unknown label '" + name + "' (known: " + knownLabelNames() + ")");
}

Label labelFromId(unsigned id)
{
	if (id >= kLabelCount)
		throw UnknownLabelError(
		    "unknown label id " + std::to_string(id) + " (known: 0.." +
		    std::to_string(kLabelCount - 1) + ")");
	return static_cast<Label>(id);
}

std::vector<Label> LabelSet::labels() const
{
	std::vector<Label> out;
	for (Label l : allLabels())
		if (contains(l)) out.push_back(l);
	return out;
}

}  // namespace semnav
