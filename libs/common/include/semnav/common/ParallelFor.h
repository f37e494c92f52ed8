/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace semnav
{
/** `requested` threads, or all cores when it is 0 or less. */
inline int resolveThreads(int requested)
{
	if (requested > 0) return requested;
	return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

/** Runs f(0) .. f(n - 1) on up to resolveThreads(threads) threads (the
 * calling one included), each thread taking the next index in order; the
 * first exception thrown is rethrown once all are done. */
template <class F>
void parallelFor(std::size_t n, int threads, const F& f)
{
	const std::size_t workers =
	    std::min(n, static_cast<std::size_t>(resolveThreads(threads)));
	if (workers <= 1)
	{
		for (std::size_t i = 0; i < n; i++) f(i);
		return;
	}
	std::atomic<std::size_t> next{0};
	std::exception_ptr error;
	std::mutex errorMutex;
	const auto work = [&]
	{
		for (std::size_t i; (i = next++) < n;)
		{
			try
			{
				f(i);
			}
			catch (...)
			{
				const std::lock_guard<std::mutex> lock(errorMutex);
				if (!error) error = std::current_exception();
			}
		}
	};
	std::vector<std::thread> pool;
	for (std::size_t w = 1; w < workers; w++) pool.emplace_back(work);
	work();
	for (auto& t : pool) t.join();
	if (error) std::rethrow_exception(error);
}

}  // namespace semnav
