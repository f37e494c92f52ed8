/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/runtime/CommandQueue.h>

#include <chrono>

namespace semnav
{
void CommandQueue::push(const std::string& line)
{
	{
		std::lock_guard<std::mutex> lk(m_mutex);
		m_lines.push_back(line);
	}
	m_cv.notify_all();
}

void CommandQueue::close()
{
	{
		std::lock_guard<std::mutex> lk(m_mutex);
		m_closed = true;
	}
	m_cv.notify_all();
}

std::optional<std::string> CommandQueue::pop(double seconds)
{
	std::unique_lock<std::mutex> lk(m_mutex);
	m_cv.wait_for(
	    lk, std::chrono::duration<double>(seconds),
	    [this] { return !m_lines.empty() || m_closed; });
	if (m_lines.empty()) return std::nullopt;
	std::string line = std::move(m_lines.front());
	m_lines.pop_front();
	return line;
}

bool CommandQueue::closed() const
{
	std::lock_guard<std::mutex> lk(m_mutex);
	return m_closed && m_lines.empty();
}

}  // namespace semnav
