/* semnav: semantic navigation from tilting-laser sweeps */
// NavCommand: the accepted forms, and one-line errors for the rest.
#include <gtest/gtest.h>
#include <semnav/common/Error.h>
#include <semnav/nav/NavCommand.h>
#include <semnav/nav/NavigationErrors.h>

using namespace semnav;

TEST(NavCommand, NearestLabel)
{
	for (const char* t :
	     {"go to the nearest wastebasket", "Go To The Nearest  WASTEBASKET",
	      "go to nearest wastebasket"})
	{
		const auto c = NavCommand::parse(t);
		EXPECT_EQ(c.kind, NavCommand::Kind::NearestLabel) << t;
		EXPECT_EQ(c.label, Label::Wastebasket) << t;
	}
	EXPECT_EQ(
	    NavCommand::parse("go to the nearest washbasin").text(),
	    "go to the nearest washbasin");
}

TEST(NavCommand, ObjectAndPoint)
{
	const auto o = NavCommand::parse("go to wastebasket 3");
	EXPECT_EQ(o.kind, NavCommand::Kind::Object);
	EXPECT_EQ(o.label, Label::Wastebasket);
	EXPECT_EQ(o.objectId, 3);
	EXPECT_EQ(NavCommand::parse("go to door #2").objectId, 2);
	const auto p = NavCommand::parse("go to 4.5 -1.25");
	EXPECT_EQ(p.kind, NavCommand::Kind::Point);
	EXPECT_DOUBLE_EQ(p.x, 4.5);
	EXPECT_DOUBLE_EQ(p.y, -1.25);
	EXPECT_EQ(NavCommand::parse("go to 4.5,2").kind, NavCommand::Kind::Point);
}

TEST(NavCommand, UnknownLabelListsTheKnownOnes)
{
	try
	{
		NavCommand::parse("go to the nearest sofa");
		FAIL() << "no error";
	}
	catch (const UnknownLabelError& e)
	{
		const std::string m = e.what();
		EXPECT_NE(m.find("sofa"), std::string::npos) << m;
		EXPECT_NE(m.find("wastebasket"), std::string::npos) << m;
		EXPECT_NE(m.find("washbasin"), std::string::npos) << m;
		EXPECT_EQ(m.find('\n'), std::string::npos) << m;
	}
	EXPECT_THROW(NavCommand::parse("go to sofa 2"), UnknownLabelError);
}

TEST(NavCommand, MalformedCommands)
{
	for (const char* t :
	     {"", "go", "go to", "walk to the nearest door", "go to door 0",
	      "go to the nearest", "go to 1 2 3", "go to the nearest door now",
	      "go to door -1"})
		EXPECT_THROW(NavCommand::parse(t), Error) << t;
}

TEST(NavCommand, CoordinatesOutOfRangeAreNoLabels)
{
	const std::pair<const char*, const char*> cases[] = {
	    {"go to 1e400 2", "coordinate 1e400 is out of range"},
	    {"go to 2 -1e999", "coordinate -1e999 is out of range"},
	    {"go to nan 2", "coordinate nan is not a finite number"},
	    {"go to 3,inf", "coordinate inf is not a finite number"},
	};
	for (const auto& [text, message] : cases)
	{
		try
		{
			NavCommand::parse(text);
			FAIL() << text << ": no error";
		}
		catch (const NavCommandError& e)
		{
			EXPECT_EQ(std::string(e.what()), message) << text;
		}
		catch (const std::exception& e)
		{
			FAIL() << text << ": " << e.what();
		}
	}
}

TEST(NavCommand, BinaryGarbageIsEchoedEscaped)
{
	try
	{
		NavCommand::parse("go to \x01\xff\x1b[2J now please");
		FAIL() << "no error";
	}
	catch (const NavCommandError& e)
	{
		const std::string m = e.what();
		EXPECT_NE(
		    m.find("'go to \\x01\\xFF\\x1B[2J now please'"), std::string::npos)
		    << m;
	}
}
