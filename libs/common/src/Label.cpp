/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/ClassRegistry.h>
#include <semnav/common/Error.h>
#include <semnav/common/Label.h>
#include <semnav/common/LabelSet.h>
#include <semnav/common/Printable.h>

namespace semnav
{
const std::vector<Label>& allLabels()
{
	return ClassRegistry::instance().labels();
}

const std::string& labelName(Label l)
{
	const auto& registry = ClassRegistry::instance();
	return registry.info(registry.contains(l) ? l : Label::Unknown).name;
}

std::string knownLabelNames()
{
	std::string s;
	for (Label l : allLabels())
	{
		if (!s.empty()) s += ", ";
		s += labelName(l);
	}
	return s;
}

Label labelFromName(const std::string& name)
{
	if (const auto l = ClassRegistry::instance().find(name)) return *l;
	throw UnknownLabelError(
	    "unknown label '" + printable(name) + "' (known: " + knownLabelNames() +
	    ")");
}

Label labelFromId(unsigned id)
{
	if (id >= ClassRegistry::instance().size())
		throw UnknownLabelError(
		    "unknown label id " + std::to_string(id) + " (known: 0.." +
		    std::to_string(ClassRegistry::instance().size() - 1) + ")");
	return static_cast<Label>(id);
}

std::vector<Label> LabelSet::labels() const
{
	std::vector<Label> out;
	for (unsigned i = 0; i < kMaxLabelCount; i++)
		if (m_mask & (mask_t(1) << i)) out.push_back(static_cast<Label>(i));
	return out;
}

}  // namespace semnav
