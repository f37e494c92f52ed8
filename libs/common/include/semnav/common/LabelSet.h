/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/common/Label.h>

#include <cstdint>
#include <vector>

namespace semnav
{
/** A set of labels as a bitmask (bit i = label id i): the paper's "list of
 * labels attached to each cell". Holds ids below kMaxLabelCount. */
class LabelSet
{
public:
	using mask_t = uint32_t;

	LabelSet() = default;
	explicit LabelSet(mask_t mask) : m_mask(mask) {}

	void insert(Label l) { m_mask |= bit(l); }
	void erase(Label l) { m_mask &= ~bit(l); }
	bool contains(Label l) const { return (m_mask & bit(l)) != 0; }
	bool empty() const { return m_mask == 0; }
	mask_t mask() const { return m_mask; }
	/** The labels in the set, in id order. */
	std::vector<Label> labels() const;

	bool operator==(const LabelSet& o) const { return m_mask == o.m_mask; }
	bool operator!=(const LabelSet& o) const { return m_mask != o.m_mask; }

private:
	static mask_t bit(Label l)
	{
		const auto i = static_cast<unsigned>(l);
		return i < kMaxLabelCount ? mask_t(1) << i : 0;
	}
	mask_t m_mask = 0;
};

}  // namespace semnav
