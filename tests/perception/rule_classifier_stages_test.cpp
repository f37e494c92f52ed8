/* semnav: semantic navigation from tilting-laser sweeps */
/* RuleClassifier's stages on their own (libs/perception/src/RuleClassifier*).
 */
#include <gtest/gtest.h>

#include <vector>

#include "../../libs/perception/src/RuleClassifierDetail.h"

using semnav::detail::rules::otsuSplit;

TEST(RuleClassifierStages, OtsuSplitsTwoModesBetweenThem)
{
	// Residuals of a wall (bins 20..29) and of a door recessed behind it
	// (bins 70..79, fewer pixels).
	std::vector<int> hist(100, 0);
	for (int b = 20; b < 30; b++) hist[b] = 30;
	for (int b = 70; b < 80; b++) hist[b] = 10;
	const auto s = otsuSplit(hist);
	ASSERT_GE(s.bin, 29);
	ASSERT_LT(s.bin, 70);
	EXPECT_DOUBLE_EQ(s.total, 400);
	EXPECT_DOUBLE_EQ(s.lowCount, 300);
	EXPECT_DOUBLE_EQ(s.lowMean, 25.0);   // centre of bins 20..29
	EXPECT_DOUBLE_EQ(s.highMean, 75.0);  // centre of bins 70..79
}

TEST(RuleClassifierStages, OtsuFindsNoSplitInOneBin)
{
	std::vector<int> hist(50, 0);
	hist[12] = 100;
	EXPECT_EQ(otsuSplit(hist).bin, -1);
	EXPECT_EQ(otsuSplit(std::vector<int>(50, 0)).bin, -1);
}

TEST(RuleClassifierStages, UnionFindRootsAreSmallestMembers)
{
	std::vector<int> uf = {0, 1, 2, 3, 4, 5};
	semnav::detail::rules::unite(uf.data(), 4, 2);
	semnav::detail::rules::unite(uf.data(), 5, 4);
	semnav::detail::rules::unite(uf.data(), 3, 1);
	EXPECT_EQ(semnav::detail::rules::findRoot(uf.data(), 5), 2);
	EXPECT_EQ(semnav::detail::rules::findRoot(uf.data(), 3), 1);
	EXPECT_EQ(semnav::detail::rules::findRoot(uf.data(), 0), 0);
}
