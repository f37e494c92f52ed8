/* semnav: semantic navigation from tilting-laser sweeps */
#include "BucketQueue.h"

#include <algorithm>

namespace semnav::detail
{
void BucketQueue::push(double value, std::size_t cell)
{
	m_size++;
	if (!m_started)
	{
		m_staged.push_back({value, cell});
		return;
	}
	place(std::max(key(value), m_cur), {value, cell});
}

void BucketQueue::place(std::int64_t k, const Entry& e)
{
	if (k >= m_cur + kRing)
	{
		m_far.push({k, e});
		return;
	}
	m_ring[static_cast<std::size_t>(k % kRing)].push_back(e);
	m_inRing++;
}

void BucketQueue::start()
{
	m_started = true;
	m_ring.resize(kRing);
	std::int64_t least = INT64_MAX;
	for (const Entry& e : m_staged) least = std::min(least, key(e.value));
	m_cur = least;
	for (const Entry& e : m_staged) place(key(e.value), e);
	m_staged.clear();
}

bool BucketQueue::pop(Entry& e)
{
	if (m_size == 0) return false;
	if (!m_started) start();
	for (;;)
	{
		auto& bucket = m_ring[static_cast<std::size_t>(m_cur % kRing)];
		if (!bucket.empty())
		{
			e = bucket.back();
			bucket.pop_back();
			m_inRing--;
			m_size--;
			return true;
		}
		m_cur = m_inRing == 0 ? m_far.top().key : m_cur + 1;
		while (!m_far.empty() && m_far.top().key < m_cur + kRing)
		{
			const Far f = m_far.top();
			m_far.pop();
			place(f.key, f.entry);
		}
	}
}

}  // namespace semnav::detail
