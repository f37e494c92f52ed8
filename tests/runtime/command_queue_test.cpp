/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <semnav/runtime/CommandQueue.h>

#include <thread>

using semnav::CommandQueue;

TEST(CommandQueue, LinesComeOutInOrderAcrossThreads)
{
	CommandQueue q;
	std::thread writer(
	    [&]
	    {
		    for (int i = 0; i < 100; i++) q.push(std::to_string(i));
		    q.close();
	    });
	int expected = 0;
	while (true)
	{
		const auto line = q.pop(1.0);
		if (!line)
		{
			if (q.closed()) break;
			continue;
		}
		EXPECT_EQ(*line, std::to_string(expected++));
	}
	writer.join();
	EXPECT_EQ(expected, 100);
}

TEST(CommandQueue, PopWaitsAtMostItsTimeout)
{
	CommandQueue q;
	const auto t0 = std::chrono::steady_clock::now();
	EXPECT_FALSE(q.pop(0.05));
	EXPECT_GE(
	    std::chrono::steady_clock::now() - t0, std::chrono::milliseconds(45));
	EXPECT_FALSE(q.closed());
	q.push("a");
	q.close();
	EXPECT_FALSE(q.closed());
	EXPECT_EQ(*q.pop(), "a");
	EXPECT_TRUE(q.closed());
}
