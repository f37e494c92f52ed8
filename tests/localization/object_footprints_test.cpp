/* semnav: semantic navigation from tilting-laser sweeps */
// ObjectFootprints: a post's footprint is its centre, not the centroid of
// the faces the sweep sees; wall fragments, wide objects, sides seen edge-on
// and table tops are no footprint; footprints score highest at the pose that
// put them on the landmarks of earlier sweeps; new objects are not scored;
// options are checked.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <semnav/common/Error.h>
#include <semnav/localization/ObjectFootprints.h>
#include <semnav/perception/LabeledSweep.h>

#include <cmath>

using namespace semnav;

namespace
{
constexpr int kRows = 20, kCols = 280;

LabeledSweep emptySweep()
{
	LabeledSweep s;
	s.labels = cv::Mat(kRows, kCols, CV_8U, cv::Scalar(0));
	const float nan = std::numeric_limits<float>::quiet_NaN();
	s.points = cv::Mat(kRows, kCols, CV_32FC3, cv::Scalar(nan, nan, nan));
	s.groundZ = 0;
	return s;
}

/** Columns [c0, c0 + 40) of `s`: the visible half of a cylinder of radius r
 * at (x, y) (robot frame), seen from the origin, from z0 to z1. */
void addCylinder(
    LabeledSweep& s, int c0, double x, double y, double r, double z0, double z1,
    Label l = Label::Obstacle)
{
	const double toward = std::atan2(-y, -x);
	for (int c = 0; c < 40; c++)
	{
		const double a = toward + (c - 19.5) / 20.0 * 1.4;
		for (int row = 0; row < kRows; row++)
		{
			const double z = z0 + (z1 - z0) * row / (kRows - 1);
			s.points.at<cv::Vec3f>(row, c0 + c) = cv::Vec3f(
			    float(x + r * std::cos(a)), float(y + r * std::sin(a)),
			    float(z));
			s.labels.at<uint8_t>(row, c0 + c) = static_cast<uint8_t>(l);
		}
	}
}

/** Columns [c0, c0 + 40): a straight face from (x0, y0) to (x1, y1). */
void addFace(
    LabeledSweep& s, int c0, double x0, double y0, double x1, double y1,
    double z0, double z1, Label l)
{
	for (int c = 0; c < 40; c++)
		for (int row = 0; row < kRows; row++)
		{
			const double t = c / 39.0;
			const double z = z0 + (z1 - z0) * row / (kRows - 1);
			s.points.at<cv::Vec3f>(row, c0 + c) = cv::Vec3f(
			    float(x0 + t * (x1 - x0)), float(y0 + t * (y1 - y0)), float(z));
			s.labels.at<uint8_t>(row, c0 + c) = static_cast<uint8_t>(l);
		}
}
}  // namespace

TEST(ObjectFootprints, APostsFootprintIsItsCentre)
{
	LabeledSweep s = emptySweep();
	addCylinder(s, 0, 3.0, 1.0, 0.15, 0.0, 1.0);
	const auto f = ObjectFootprints().extract(s);
	ASSERT_EQ(f.size(), 1u);
	EXPECT_NEAR(f[0].radius, 0.15, 0.03);
	const double err = std::hypot(f[0].x - 3.0, f[0].y - 1.0);
	EXPECT_LE(err, 0.03);
	// The centroid of the visible faces lies well short of the centre.
	double mx = 0, my = 0, n = 0;
	for (int c = 0; c < 40; c++)
	{
		const auto& p = s.points.at<cv::Vec3f>(0, c);
		mx += p[0], my += p[1], n++;
	}
	EXPECT_GE(std::hypot(mx / n - 3.0, my / n - 1.0), 3 * err);
}

TEST(ObjectFootprints, WallFragmentsWideObjectsAndTableTopsAreNoFootprint)
{
	LabeledSweep s = emptySweep();
	// An obstacle piece against a wall face.
	addFace(s, 0, 4.0, -1.0, 4.0, 1.0, 0.0, 2.5, Label::Wall);
	addCylinder(s, 40, 3.8, 0.0, 0.05, 0.0, 1.0);
	// A 1.2 m wide object.
	addFace(s, 80, 2.0, 2.0, 2.0, 3.2, 0.0, 0.8, Label::Obstacle);
	// A table top 0.7 m above the ground.
	addCylinder(s, 120, -3.0, 0.0, 0.2, 0.7, 0.75);
	// Two pieces of one object 0.2 m apart.
	addCylinder(s, 160, 0.0, -3.0, 0.05, 0.0, 1.0);
	addCylinder(s, 200, 0.0, -3.25, 0.05, 0.0, 1.0);
	// A side seen edge-on (along the ray: no width across it).
	addFace(s, 240, 0.0, 5.0, 0.0, 5.3, 0.0, 0.8, Label::Obstacle);
	EXPECT_TRUE(ObjectFootprints().extract(s).empty());
	// The same post alone in the open is one.
	LabeledSweep alone = emptySweep();
	addCylinder(alone, 40, 3.8, 0.0, 0.05, 0.0, 1.0);
	EXPECT_EQ(ObjectFootprints().extract(alone).size(), 1u);
}

TEST(ObjectFootprints, TheTruePoseScoresHighestAndNewObjectsAreNotScored)
{
	ObjectFootprints::TOptions o;
	o.minSweeps = 2;
	ObjectFootprints map(o);
	// Two posts, seen from (0, 0) and (1, 0) (robot frames).
	const std::vector<ObjectFootprints::Footprint> first = {
	    {5, 0, 0.05, 1}, {5, 3, 0.05, 1}};
	const std::vector<ObjectFootprints::Footprint> second = {
	    {4, 0, 0.05, 1}, {4, 3, 0.05, 1}};
	map.insert(first, mrpt::poses::CPose2D(0, 0, 0));
	// Seen from one sweep only: not yet scored.
	EXPECT_TRUE(map.observedPart(1, 0, 0, second).empty());
	map.insert(second, mrpt::poses::CPose2D(1, 0, 0));
	ASSERT_EQ(map.landmarks().size(), 2u);
	EXPECT_EQ(map.landmarks()[0].sweeps, 2);

	// A third sweep from (2, 0.5), with a new post far from both.
	std::vector<ObjectFootprints::Footprint> third = {
	    {3, -0.5, 0.05, 1}, {3, 2.5, 0.05, 1}, {1, -4, 0.05, 1}};
	const auto scored = map.observedPart(2, 0.5, 0, third);
	ASSERT_EQ(scored.size(), 2u);
	const double truth = map.logLikelihood(2, 0.5, 0, scored);
	EXPECT_GT(truth, map.logLikelihood(2.2, 0.5, 0, scored));
	EXPECT_GT(truth, map.logLikelihood(2, 0.7, 0, scored));
	EXPECT_GT(truth, map.logLikelihood(2, 0.5, 0.05, scored));
	// Off: every pose alike.
	o.points = 0;
	ObjectFootprints off(o);
	off.insert(first, mrpt::poses::CPose2D(0, 0, 0));
	off.insert(second, mrpt::poses::CPose2D(1, 0, 0));
	EXPECT_EQ(off.logLikelihood(2, 0.5, 0, scored), 0);
}

TEST(ObjectFootprints, OptionsRejectUnknownKeysAndOutOfRange)
{
	const auto load = [](const std::string& text)
	{
		mrpt::config::CConfigFileMemory c(text);
		ObjectFootprints::TOptions o;
		o.loadFromConfigFile(c, "ObjectFootprints");
		return o;
	};
	EXPECT_FALSE(load("[ObjectFootprints]\npoints = 0\n").enabled());
	EXPECT_EQ(load("[ObjectFootprints]\nmin_sweeps = 3\n").minSweeps, 3);
	EXPECT_THROW(load("[ObjectFootprints]\npoint = 1\n"), ConfigError);
	EXPECT_THROW(load("[ObjectFootprints]\nsigma_m = 0\n"), ConfigError);
	EXPECT_THROW(load("[ObjectFootprints]\nmin_sweeps = 0\n"), ConfigError);
}
