/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <semnav/common/ParallelFor.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

using namespace semnav;

TEST(ParallelFor, RunsEveryIndexOnceOnSeveralThreads)
{
	for (const int threads : {0, 1, 2, 3, 8})
	{
		std::vector<std::atomic<int>> runs(37);
		std::set<std::thread::id> ids;
		std::mutex m;
		parallelFor(
		    runs.size(), threads,
		    [&](std::size_t i)
		    {
			    runs[i]++;
			    // Long enough for the other threads to take indices.
			    std::this_thread::sleep_for(std::chrono::milliseconds(2));
			    const std::lock_guard<std::mutex> lock(m);
			    ids.insert(std::this_thread::get_id());
		    });
		for (const auto& r : runs) EXPECT_EQ(r.load(), 1) << threads;
		EXPECT_LE(
		    ids.size(), static_cast<std::size_t>(resolveThreads(threads)));
		if (threads == 1)
		{
			EXPECT_EQ(ids.size(), 1u);
			EXPECT_EQ(*ids.begin(), std::this_thread::get_id());
		}
		if (threads >= 2) EXPECT_GE(ids.size(), 2u) << threads;
	}
	EXPECT_GE(resolveThreads(0), 1);
	EXPECT_EQ(resolveThreads(3), 3);
}

TEST(ParallelFor, RethrowsAfterEveryIndexRan)
{
	std::atomic<int> ran{0};
	EXPECT_THROW(
	    parallelFor(
	        10, 2,
	        [&](std::size_t i)
	        {
		        ran++;
		        if (i == 3) throw std::runtime_error("index 3");
	        }),
	    std::runtime_error);
	EXPECT_EQ(ran.load(), 10);
	// No indices: nothing runs.
	parallelFor(0, 4, [&](std::size_t) { ran++; });
	EXPECT_EQ(ran.load(), 10);
}
