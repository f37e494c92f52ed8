/* semnav: semantic navigation from tilting-laser sweeps */
#include "BucketQueue.h"

#include <algorithm>

namespace semnav::detail
{
void BucketQueue::push(double value, std::size_t cell, double priority)
{
	m_size++;
	if (!m_started)
	{
		m_staged.push_back({{value, cell}, key(priority)});
		return;
	}
	const std::int64_t k = std::max(key(priority), m_popped);
	if (k < m_base) lowerBase(k);
	place(k, {value, cell});
}

void BucketQueue::lowerBase(std::int64_t k)
{
	// Buckets leaving the ring's end wait in the heap.
	for (std::int64_t b = std::max(k + kRing, m_base); b < m_base + kRing; b++)
	{
		auto& bucket = m_ring[static_cast<std::size_t>(b % kRing)];
		for (const Entry& e : bucket) m_far.push({b, e});
		m_inRing -= bucket.size();
		bucket.clear();
	}
	m_base = k;
	m_cur = std::min(m_cur, k);
}

void BucketQueue::place(std::int64_t k, const Entry& e)
{
	if (k >= m_base + kRing)
	{
		m_far.push({k, e});
		return;
	}
	m_ring[static_cast<std::size_t>(k % kRing)].push_back(e);
	m_inRing++;
	m_cur = std::min(m_cur, k);
}

void BucketQueue::start()
{
	m_started = true;
	m_ring.resize(kRing);
	std::int64_t least = INT64_MAX;
	for (const Staged& e : m_staged) least = std::min(least, e.key);
	m_base = m_cur = least;
	for (const Staged& e : m_staged) place(e.key, e.entry);
	m_staged.clear();
}

std::int64_t BucketQueue::front()
{
	if (!m_started) start();
	if (m_inRing == 0) return m_far.top().key;
	while (m_ring[static_cast<std::size_t>(m_cur % kRing)].empty()) m_cur++;
	return m_cur;
}

void BucketQueue::advanceBase(std::int64_t k)
{
	if (k == m_base) return;
	m_base = k;
	m_cur = std::max(m_cur, k);
	while (!m_far.empty() && m_far.top().key < m_base + kRing)
	{
		const Far f = m_far.top();
		m_far.pop();
		place(f.key, f.entry);
	}
}

bool BucketQueue::peek(std::int64_t& bucket)
{
	if (m_size == 0) return false;
	bucket = front();
	return true;
}

bool BucketQueue::pop(Entry& e)
{
	if (m_size == 0) return false;
	const std::int64_t k = front();
	advanceBase(k);
	m_popped = k;
	auto& bucket = m_ring[static_cast<std::size_t>(k % kRing)];
	e = bucket.back();
	bucket.pop_back();
	m_inRing--;
	m_size--;
	return true;
}

}  // namespace semnav::detail
