/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <semnav/common/Error.h>
#include <semnav/common/Label.h>
#include <semnav/common/LabelSet.h>

using namespace semnav;

TEST(Label, NamesRoundTripInDesignOrder)
{
	const char* expected[] = {"unknown",   "floor",       "ceiling", "wall",
	                          "door",      "sidewalk",    "grass",   "stairs",
	                          "washbasin", "wastebasket", "obstacle"};
	ASSERT_EQ(allLabels().size(), std::size(expected));
	for (std::size_t i = 0; i < kBuiltInLabelCount; i++)
	{
		EXPECT_EQ(labelName(static_cast<Label>(i)), expected[i]);
		EXPECT_EQ(static_cast<std::size_t>(labelFromName(expected[i])), i);
		EXPECT_EQ(labelFromId(static_cast<unsigned>(i)), static_cast<Label>(i));
	}
}

TEST(Label, UnknownNameListsTheKnownOnes)
{
	try
	{
		labelFromName("wastebin");
		FAIL() << "accepted an unknown label";
	}
	catch (const UnknownLabelError& e)
	{
		const std::string m = e.what();
		EXPECT_NE(m.find("'wastebin'"), std::string::npos);
		EXPECT_NE(m.find("wastebasket"), std::string::npos);
	}
	EXPECT_THROW(labelFromId(11), UnknownLabelError);
}

TEST(LabelSet, HoldsSeveralLabelsPerCell)
{
	LabelSet s;
	EXPECT_TRUE(s.empty());
	s.insert(Label::Floor);
	s.insert(Label::Wastebasket);
	s.insert(Label::Floor);
	EXPECT_TRUE(s.contains(Label::Floor));
	EXPECT_TRUE(s.contains(Label::Wastebasket));
	EXPECT_FALSE(s.contains(Label::Wall));
	EXPECT_EQ(s.labels().size(), 2u);
	EXPECT_EQ(s.mask(), (1u << 1) | (1u << 9));
	s.erase(Label::Floor);
	EXPECT_EQ(s.labels(), std::vector<Label>{Label::Wastebasket});
	EXPECT_EQ(LabelSet(s.mask()), s);
}
