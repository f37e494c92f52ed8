/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <condition_variable>
#include <deque>
#include <mutex>
#include <optional>
#include <string>

namespace semnav
{
/** Operator commands, one text line each, from any thread (stdin, a ROS
 * topic) to the robot's control loop, in order. close() marks the end of
 * the input: pop() then returns nothing once the queue is empty. */
class CommandQueue
{
public:
	void push(const std::string& line);
	/** No more lines will come. */
	void close();
	/** The next line, waiting at most `seconds`; nothing on timeout or
	 * when closed and empty. */
	std::optional<std::string> pop(double seconds = 0);
	bool closed() const;

private:
	mutable std::mutex m_mutex;
	std::condition_variable m_cv;
	std::deque<std::string> m_lines;
	bool m_closed = false;
};

}  // namespace semnav
