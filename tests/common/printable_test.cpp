/* semnav: semantic navigation from tilting-laser sweeps */
// printable(): what error messages echo of their input.
#include <gtest/gtest.h>
#include <semnav/common/Error.h>
#include <semnav/common/Label.h>
#include <semnav/common/Printable.h>

using namespace semnav;

TEST(Printable, EscapesBytesThatDoNotPrintAndKeepsUtf8)
{
	EXPECT_EQ(printable("go to door 2"), "go to door 2");
	EXPECT_EQ(printable(std::string("a\0b", 3)), "a\\x00b");
	EXPECT_EQ(
	    printable("x\ny\r\t\x1b[31m\x7f"), "x\\x0Ay\\x0D\\x09\\x1B[31m\\x7F");
	EXPECT_EQ(
	    printable("caf\xc3\xa9 \xe2\x82\xac"), "caf\xc3\xa9 \xe2\x82\xac");
	// Invalid UTF-8: a lone continuation byte, a cut sequence, an overlong
	// form, a C1 control.
	EXPECT_EQ(printable("\x80\xff"), "\\x80\\xFF");
	EXPECT_EQ(printable("\xe2\x82"), "\\xE2\\x82");
	EXPECT_EQ(printable("\xc0\xaf"), "\\xC0\\xAF");
	EXPECT_EQ(printable("\xc2\x85"), "\\xC2\\x85");
	const std::string once = printable("\x01\xfe garbage \x9b");
	EXPECT_EQ(printable(once), once);
}

TEST(Printable, UnknownLabelEchoesTheNameEscaped)
{
	try
	{
		labelFromName("sofa\x01\xff\n");
		FAIL() << "no error";
	}
	catch (const UnknownLabelError& e)
	{
		const std::string m = e.what();
		EXPECT_NE(m.find("'sofa\\x01\\xFF\\x0A'"), std::string::npos) << m;
	}
}
