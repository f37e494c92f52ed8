/* semnav: semantic navigation from tilting-laser sweeps */
// Mapping with localization outdoors (MapBuilder, --poses pf, shipped
// config/localization.ini) on semnav-sim runs of datasets/outdoor: the
// filter beats the odometry on every run and stays within 0.15 m where a
// door gap, a second wall, a path's edge or posts and bins (their
// footprints) fix the position (campus_heldout was written after the method
// was built); along a single long wall the estimate follows the odometry and
// the reported covariance is long along the wall.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/core/bits_math.h>
#include <semnav/common/ConfigChecks.h>
#include <semnav/mapping/MapBuilder.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <utility>

#include "../TestPaths.h"

using namespace semnav;
namespace fs = std::filesystem;

namespace
{

/** semnav-sim's run of datasets/outdoor/<scene>.yaml (directory). */
fs::path simulate(const std::string& scene, int seed)
{
	const fs::path dir = fs::temp_directory_path() /
	                     ("semnav_outdoor_" + std::to_string(::getpid()) + "_" +
	                      scene + std::to_string(seed));
	fs::remove_all(dir);
	const std::string cmd = std::string(SEMNAV_BINARY_DIR) +
	                        "/apps/semnav-sim/semnav-sim --scene " +
	                        test::kSourceDir + "/datasets/outdoor/" + scene +
	                        ".yaml --out " + dir.string() + " --seed " +
	                        std::to_string(seed) + " > /dev/null";
	EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
	return dir;
}

/** Maps the run with --poses pf and the shipped localization config. */
std::unique_ptr<MapBuilder> mapRun(const std::string& scene, int seed)
{
	const fs::path dir = simulate(scene, seed);
	MapBuilder::Settings s;
	s.localization.loadFromConfigFile(
	    *openIniFile(
	        test::kSourceDir + "/config/localization.ini",
	        MappingLocalizer::TOptions::sections()),
	    "");
	s.poses = MapBuilder::PoseSource::Localization;
	s.rawlog = (dir / (scene + ".rawlog")).string();
	s.gtDir = dir.string();
	auto b = std::make_unique<MapBuilder>(s);
	b->run();
	fs::remove_all(dir);
	return b;
}
}  // namespace

TEST(MappingLocalizerOutdoor, BeatsOdometryWithinFifteenCentimetres)
{
	const std::pair<const char*, int> runs[] = {
	    {"outdoor", 1},        {"outdoor", 2},        {"outdoor", 3},
	    {"campus_corner", 1},  {"campus_corner", 2},  {"campus_corner", 3},
	    {"campus_quad", 1},    {"campus_quad", 2},    {"campus_quad", 3},
	    {"campus_heldout", 1}, {"campus_heldout", 2}, {"campus_heldout", 3}};
	for (const auto& [scene, seed] : runs)
	{
		const auto b = mapRun(scene, seed);
		ASSERT_GT(b->poseError().size(), 5u);
		const double pf = b->poseError().rmseXY();
		const double odo = b->odometryError().rmseXY();
		EXPECT_LE(pf, 0.15) << scene << " seed " << seed;
		EXPECT_LT(pf, odo) << scene << " seed " << seed;
		EXPECT_LE(mrpt::RAD2DEG(b->poseError().maxYaw()), 6.0)
		    << scene << " seed " << seed;
	}
}

TEST(MappingLocalizerOutdoor, NeverWorseThanOdometryWhereNotWithinBound)
{
	// The long wall, where nothing fixes the position along it after the
	// bin at the start (seed 1: SingleWallCovarianceIsLongAlongTheWall): the
	// filter still beats the odometry.
	const std::pair<const char*, int> runs[] = {
	    {"campus_long_wall", 2}, {"campus_long_wall", 3}};
	for (const auto& [scene, seed] : runs)
	{
		const auto b = mapRun(scene, seed);
		EXPECT_LT(b->poseError().rmseXY(), b->odometryError().rmseXY())
		    << scene << " seed " << seed;
	}
}

TEST(MappingLocalizerOutdoor, SingleWallCovarianceIsLongAlongTheWall)
{
	const auto b = mapRun("campus_long_wall", 1);
	const auto& ups = b->localizationUpdates();
	ASSERT_GE(ups.size(), 6u);
	EXPECT_LT(b->poseError().rmseXY(), b->odometryError().rmseXY());
	int followed = 0;
	for (const auto& u : ups) followed += u.unconstrained > 0;
	// Nothing fixes x on most updates: the estimate followed the odometry.
	EXPECT_GE(followed, static_cast<int>(ups.size()) - 1);
	const auto& last = ups.back();
	// The wall runs along x (0 deg): the largest std is along it, several
	// times the std across it.
	EXPECT_LE(std::abs(mrpt::RAD2DEG(last.largestStdDirection)), 15.0);
	EXPECT_GE(last.largestStd, 0.2);
	EXPECT_LE(std::sqrt(std::max(0.0, last.cov(1, 1))), last.largestStd / 3);
	// Across the wall and in heading the walls hold the estimate.
	EXPECT_LE(mrpt::RAD2DEG(b->poseError().maxYaw()), 1.0);
}
