/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/common/ClassInfo.h>
#include <semnav/common/Label.h>
#include <semnav/common/LabelSet.h>

#include <deque>
#include <optional>
#include <string>
#include <vector>

namespace semnav
{
/** The table of semantic classes: one ClassInfo row per Label id. It starts
 * with the 11 built-in classes (ids 0..10, the file-format contract of label
 * images); add() appends a class with the next id. Readers (map, renderers,
 * travel cost, planning, scene tools, name parsing) take their per-class
 * knowledge from here (see docs/classes.md).
 *
 * Register extra classes at start-up, before other threads read the table
 * and before building objects whose options take per-class defaults
 * (TraversabilityBuilder, TravelCostModel). Rows are never removed except
 * by resetToBuiltIns(), and references to them stay valid. */
class ClassRegistry
{
public:
	/** The process-wide table. */
	static ClassRegistry& instance();

	/** Appends a class with the next free id and returns its label. Throws
	 * Error when the name is empty, not lower case, already taken, or the
	 * table holds kMaxLabelCount classes. */
	Label add(ClassInfo info);

	/** The row of `l`; throws UnknownLabelError when `l` is not
	 * registered. */
	const ClassInfo& info(Label l) const;
	bool contains(Label l) const;
	/** The label called `name`, if any. */
	std::optional<Label> find(const std::string& name) const;

	/** Number of classes (Unknown included). */
	std::size_t size() const { return m_rows.size(); }
	/** All labels in id order. */
	const std::vector<Label>& labels() const { return m_labels; }

	/** The labels whose row satisfies `pred(const ClassInfo&)`. */
	template <typename Pred>
	LabelSet select(Pred&& pred) const
	{
		LabelSet out;
		for (Label l : m_labels)
			if (pred(m_rows[static_cast<std::size_t>(l)])) out.insert(l);
		return out;
	}

	/** Drops the classes added at run time (for tests). */
	void resetToBuiltIns();

private:
	ClassRegistry();

	std::deque<ClassInfo> m_rows;
	std::vector<Label> m_labels;
};

/** ClassRegistry::instance().info(l). */
const ClassInfo& classInfo(Label l);

}  // namespace semnav
