/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <semnav/cascade/CascadeError.h>
#include <semnav/cascade/CascadeXml.h>

#include <filesystem>
#include <fstream>
#include <opencv2/objdetect.hpp>

#include "CascadeTestUtils.h"

using namespace semnav;

namespace
{
/** A small hand-made cascade with upright and tilted features. */
HaarCascade smallCascade()
{
	HaarCascade c;
	c.windowSize = {20, 20};
	const auto pool = generateHaarFeatures({20, 20}, HaarMode::All);
	for (std::size_t i : {0ul, 1234ul, 40000ul, 90000ul})
		c.features.push_back(pool[i]);
	for (const auto& f : pool)
		if (f.tilted && f.count == 2 && f.rects[0].rect.x > 3)
		{
			c.features.push_back(f);
			break;
		}
	HaarCascade::Stage s0;
	s0.threshold = -0.123456789f;
	s0.stumps = {{0, 0.0123f, -0.9f, 0.8f}, {4, -1.5e-3f, 0.25f, -0.75f}};
	HaarCascade::Stage s1;
	s1.threshold = 1.0f / 3.0f;
	s1.stumps = {
	    {1, 0.1f, 1.0f / 7.0f, -2.0f / 9.0f},
	    {2, 0.2f, -0.5f, 0.5f},
	    {3, -0.3f, 0.3333333f, -0.125f}};
	c.stages = {s0, s1};
	c.params.mode = HaarMode::All;
	return c;
}

std::string errorOf(const std::string& xml)
{
	try
	{
		CascadeXml::fromString(xml, "test.xml");
	}
	catch (const CascadeError& e)
	{
		return e.what();
	}
	return "";
}

std::string replaced(std::string s, const std::string& a, const std::string& b)
{
	const auto p = s.find(a);
	EXPECT_NE(p, std::string::npos) << a;
	if (p != std::string::npos) s.replace(p, a.size(), b);
	return s;
}
}  // namespace

TEST(CascadeXml, RoundTripIsExact)
{
	HaarCascade c = smallCascade();
	c.note = "made by: semnav-train-cascade --label x --seed 3";
	const std::string xml = CascadeXml::toString(c);
	EXPECT_NE(xml.find("--label x"), std::string::npos);
	EXPECT_NE(xml.find("<stageType>BOOST</stageType>"), std::string::npos);
	EXPECT_NE(xml.find("<featureType>HAAR</featureType>"), std::string::npos);
	EXPECT_NE(xml.find("<tilted>1</tilted>"), std::string::npos);
	EXPECT_NE(xml.find("<mode>ALL</mode>"), std::string::npos);
	const HaarCascade back = CascadeXml::fromString(xml);
	EXPECT_TRUE(back == c);
	EXPECT_EQ(back.note, c.note);
	EXPECT_EQ(CascadeXml::toString(back), xml);
}

TEST(CascadeXml, FileRoundTripAndOpenCvLoadsIt)
{
	const auto dir = std::filesystem::temp_directory_path() / "semnav_xml_test";
	std::filesystem::create_directories(dir);
	const std::string path = (dir / "small.xml").string();
	CascadeXml::writeFile(path, smallCascade());
	EXPECT_TRUE(CascadeXml::readFile(path) == smallCascade());
	cv::CascadeClassifier cc;
	ASSERT_TRUE(cc.load(path));
	EXPECT_FALSE(cc.isOldFormatCascade());
	EXPECT_EQ(cc.getOriginalWindowSize(), cv::Size(20, 20));
	EXPECT_EQ(cc.getFeatureType(), 0);  // HAAR
	std::filesystem::remove_all(dir);
}

TEST(CascadeXml, ReadsOpenCvShippedCascade)
{
	const std::string path =
	    test::openCvCascade("haarcascade_frontalface_default.xml");
	if (path.empty())
		GTEST_SKIP() << "opencv-data is not installed "
		                "(/usr/share/opencv4/haarcascades missing)";
	const HaarCascade c = CascadeXml::readFile(path);
	EXPECT_EQ(c.windowSize, cv::Size(24, 24));
	EXPECT_EQ(c.stages.size(), 25u);
	EXPECT_FALSE(c.hasTiltedFeatures());
	EXPECT_EQ(c.stages[0].stumps.size(), 9u);
	EXPECT_FLOAT_EQ(c.stages[0].threshold, -5.0425500869750977f);
}

TEST(CascadeXml, CorruptXmlGivesClearErrors)
{
	const std::string good = CascadeXml::toString(smallCascade());
	EXPECT_NE(errorOf("").find("test.xml: empty file"), std::string::npos);
	EXPECT_NE(
	    errorOf("this is not XML").find("test.xml: not valid cascade XML"),
	    std::string::npos)
	    << errorOf("this is not XML");
	const std::string truncated = good.substr(0, good.size() / 2);
	EXPECT_EQ(errorOf(truncated).rfind("test.xml: ", 0), 0u)
	    << errorOf(truncated);
	EXPECT_NE(
	    errorOf(replaced(good, "<stageType>BOOST", "<stageType>LBP"))
	        .find("stageType: 'LBP' is not BOOST"),
	    std::string::npos);
	EXPECT_NE(
	    errorOf(replaced(good, "<featureType>HAAR", "<featureType>LBP"))
	        .find("'LBP' is not HAAR"),
	    std::string::npos);
	// A depth-2 tree instead of a stump.
	const std::string tree =
	    replaced(good, "0 -1 0 ", "1 -1 0 1.0e-01 0 -2 0 ");
	EXPECT_NE(
	    errorOf(tree).find("stage 0, weak classifier 0: only stumps"),
	    std::string::npos)
	    << errorOf(tree);
	const std::string badIndex = replaced(good, "0 -1 4 ", "0 -1 77 ");
	EXPECT_NE(
	    errorOf(badIndex).find("stage 0 uses feature 77 of 5"),
	    std::string::npos)
	    << errorOf(badIndex);
	const std::string noStages = replaced(good, "<stages>", "<stagez>");
	EXPECT_FALSE(errorOf(noStages).empty());
	const std::string textThreshold =
	    replaced(good, "<stageThreshold>", "<stageThreshold>abc ");
	EXPECT_NE(
	    errorOf(textThreshold).find("stage 0: stageThreshold"),
	    std::string::npos)
	    << errorOf(textThreshold);
	const std::string outside = replaced(
	    good, "<rects>\n        <_>\n          0 0 ",
	    "<rects>\n        <_>\n          19 0 ");
	EXPECT_NE(
	    errorOf(outside).find("feature 0: a rectangle leaves the window"),
	    std::string::npos)
	    << errorOf(outside);
	try
	{
		CascadeXml::readFile("/nonexistent/dir/x.xml");
		FAIL();
	}
	catch (const CascadeError& e)
	{
		EXPECT_STREQ(
		    e.what(), "cannot open cascade file /nonexistent/dir/x.xml");
	}
}

// Found by fuzz_cascade_xml (fuzz/): OpenCV's XML parser crashed (SEGV) on
// NUL bytes; they are not XML.
TEST(CascadeXml, NulBytesAreNotXml)
{
	const std::string good = CascadeXml::toString(smallCascade());
	const std::string nul =
	    replaced(good, "version=", "version=" + std::string(200, '\0'));
	EXPECT_NE(
	    errorOf(nul).find("test.xml: not XML: a NUL byte at byte 14"),
	    std::string::npos)
	    << errorOf(nul);
	std::ifstream f(
	    std::string(SEMNAV_SOURCE_DIR) +
	        "/tests/cascade/data/fuzz-cascade-nul.xml",
	    std::ios::binary);
	ASSERT_TRUE(f.good());
	const std::string crashed(std::istreambuf_iterator<char>(f), {});
	EXPECT_EQ(errorOf(crashed).rfind("test.xml: not XML", 0), 0u)
	    << errorOf(crashed);
}
