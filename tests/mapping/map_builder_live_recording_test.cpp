/* semnav: semantic navigation from tilting-laser sweeps */
// semnav-map on a robot's streamed recording (MapBuilder, its defaults):
// only the sweeps taken standing are mapped, one of them with lost lines;
// the pieces of nods taken while driving never reach perception.
#include <gtest/gtest.h>
#include <semnav/mapping/MapBuilder.h>
#include <unistd.h>

#include <filesystem>

#include "../scan/ScanTestUtils.h"

using namespace semnav;
namespace fs = std::filesystem;

TEST(MapBuilderLiveRecording, MapsTheStandingSweepsOnly)
{
	const fs::path dir = fs::temp_directory_path() /
	                     ("semnav_live_map_" + std::to_string(::getpid()));
	fs::remove_all(dir);
	fs::create_directories(dir);
	const std::string path = (dir / "robot.rawlog").string();
	test::writeStopAndScanRecording(path);

	MapBuilder::Settings s;  // rules only, odometry poses
	s.rawlog = path;
	MapBuilder builder(s);
	EXPECT_NO_THROW(builder.run());
	EXPECT_TRUE(builder.readError().empty()) << builder.readError();
	EXPECT_EQ(builder.map().sweepsInserted(), 3u);
	EXPECT_EQ(builder.msPerSweep().size(), 3u);
	EXPECT_EQ(builder.sweepsSkippedIncomplete(), 1u);  // the log's last piece
	EXPECT_GT(builder.sweepsDroppedMoving(), 10u);
	EXPECT_EQ(builder.sweepsFailed(), 0u);
	fs::remove_all(dir);
}
