/* semnav: semantic navigation from tilting-laser sweeps */
// Internal: the monotone priority queue of the field repair.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <queue>
#include <vector>

namespace semnav::detail
{
/** Cells by decreasing value v, in buckets of width `width` of L - v: pops
 * come bucket by bucket, highest values first, in any order within a
 * bucket (Dial's algorithm). With a width below the least step cost a cell
 * never offers a value to a cell of its own bucket, so the order is exact
 * where it matters. Pushes before the first pop may hold any value; later
 * ones must not be above the bucket last popped (they join it if they
 * are), but may be above the next one peek() shows. Buckets beyond a ring
 * of kRing wait in a heap. */
class BucketQueue
{
public:
	struct Entry
	{
		double value;
		std::size_t cell;
	};

	BucketQueue(double L, double width) : m_L(L), m_invWidth(1.0 / width) {}

	void push(double value, std::size_t cell) { push(value, cell, value); }
	/** Queued by `priority` instead of its value. */
	void push(double value, std::size_t cell, double priority);
	/** False when empty. */
	bool pop(Entry& e);
	/** The bucket the next pop comes from; false when empty. */
	bool peek(std::int64_t& bucket);
	bool empty() const { return m_size == 0; }

	/** Bucket of v, clamped to 2^62 (far values share the last one). */
	std::int64_t key(double v) const
	{
		const double k = (m_L - v) * m_invWidth;
		return k < 0x1p62 ? static_cast<std::int64_t>(k) : INT64_C(1) << 62;
	}

private:
	static constexpr std::int64_t kRing = 4096;
	struct Far
	{
		std::int64_t key;
		Entry entry;
		bool operator>(const Far& o) const { return key > o.key; }
	};

	void place(std::int64_t k, const Entry& e);
	/** Starts popping at the least key staged so far. */
	void start();
	/** The least non-empty bucket (the queue is not empty). */
	std::int64_t front();
	/** Moves the ring to start at bucket k (the least non-empty one). */
	void advanceBase(std::int64_t k);
	/** Moves the ring to start at bucket k, below its start. */
	void lowerBase(std::int64_t k);

	double m_L, m_invWidth;
	bool m_started = false;
	struct Staged
	{
		Entry entry;
		std::int64_t key;
	};
	std::vector<Staged> m_staged;
	std::vector<std::vector<Entry>> m_ring;
	/** The ring holds buckets [m_base, m_base + kRing); none below
	 * m_cur is filled. */
	std::int64_t m_base = 0, m_cur = 0;
	/** The bucket last popped: later pushes join it if above it. */
	std::int64_t m_popped = INT64_MIN;
	std::size_t m_size = 0, m_inRing = 0;
	std::priority_queue<Far, std::vector<Far>, std::greater<Far>> m_far;
};

}  // namespace semnav::detail
