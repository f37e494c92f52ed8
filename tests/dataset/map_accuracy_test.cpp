/* semnav: semantic navigation from tilting-laser sweeps */
// Mapping with true poses on the simulated office: occupied cells lie on
// real obstacles, doors appear once near their true centres.
#include <gtest/gtest.h>
#include <semnav/map/MapIO.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/perception/PerceptionPipeline.h>
#include <semnav/scan/GroundTruthLog.h>
#include <semnav/scan/RawlogSweepReader.h>
#include <semnav/sim/SceneLoader.h>
#include <semnav/sim/SimulationRunner.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <opencv2/imgcodecs.hpp>

using namespace semnav;
namespace fs = std::filesystem;

namespace
{
/** 2D distance from a point to a primitive's footprint (0 inside). */
double footprintDistance(const ScenePrimitive& prim, double x, double y)
{
	auto rectDist = [](double px, double py, double cx, double cy, double yaw,
	                   double hx, double hy)
	{
		const double c = std::cos(-yaw), s = std::sin(-yaw);
		const double lx = c * (px - cx) - s * (py - cy),
		             ly = s * (px - cx) + c * (py - cy);
		const double dx = std::max(0.0, std::abs(lx) - hx),
		             dy = std::max(0.0, std::abs(ly) - hy);
		return std::hypot(dx, dy);
	};
	if (const auto* b = std::get_if<BoxShape>(&prim))
		return rectDist(
		    x, y, b->center.x, b->center.y, b->yaw, b->size.x / 2,
		    b->size.y / 2);
	if (const auto* c = std::get_if<CylinderShape>(&prim))
		return std::max(
		    0.0, std::hypot(x - c->center.x, y - c->center.y) - c->radius);
	if (const auto* st = std::get_if<StairsShape>(&prim))
	{
		const double len = st->steps * st->run;
		const double cx = st->origin.x + std::cos(st->yaw) * len / 2,
		             cy = st->origin.y + std::sin(st->yaw) * len / 2;
		return rectDist(x, y, cx, cy, st->yaw, len / 2, st->width / 2);
	}
	return std::numeric_limits<double>::infinity();  // terrain is ground
}

struct MappedOffice
{
	Scene scene;
	fs::path dir;
	std::unique_ptr<SemanticMap> map;
	std::vector<int>
	    doorPixelsSeen;  // per scene object id: max pixels in one sweep
};

const MappedOffice& office()
{
	static const MappedOffice m = []
	{
		MappedOffice o;
		o.scene = SceneLoader::loadFile(
		    std::string(SEMNAV_SOURCE_DIR) + "/datasets/office/office.yaml");
		o.dir = fs::temp_directory_path() /
		        ("semnav_mapacc_" + std::to_string(::getpid()));
		fs::remove_all(o.dir);
		const auto res =
		    SimulationRunner(o.scene, SimulationRunner::TOptions(), 1)
		        .run(o.dir.string());
		const auto gt =
		    GroundTruthLog::forRawlog(o.dir.string(), res.rawlogPath);
		o.map = std::make_unique<SemanticMap>();
		PerceptionPipeline pipeline;
		RawlogSweepReader reader(res.rawlogPath);
		o.doorPixelsSeen.assign(o.scene.objects.size() + 1, 0);
		Sweep s;
		while (reader.next(s))
		{
			o.map->insert(s, pipeline.process(s), gt.pose(s.index()));
			const cv::Mat lab =
			    cv::imread(gt.labelImagePath(s.index()), cv::IMREAD_UNCHANGED);
			std::vector<int> count(o.scene.objects.size() + 1, 0);
			for (int r = 0; r < lab.rows; r++)
				for (int c = 0; c < lab.cols; c++)
				{
					const uint16_t v = lab.at<uint16_t>(r, c);
					if ((v & 0xFF) == static_cast<int>(Label::Door))
						count[v >> 8]++;
				}
			for (std::size_t i = 0; i < count.size(); i++)
				o.doorPixelsSeen[i] = std::max(o.doorPixelsSeen[i], count[i]);
		}
		return o;
	}();
	return m;
}
}  // namespace

TEST(MapAccuracy, OccupiedCellsLieOnRealObstacles)
{
	const auto& o = office();
	const auto& map = *o.map;
	const auto& g = map.geometry();
	std::size_t occupied = 0, near = 0;
	for (int cy = 0; cy < g.rows; cy++)
		for (int cx = 0; cx < g.cols; cx++)
		{
			if (map.cellState(cx, cy) != SemanticMap::CellState::Occupied)
				continue;
			occupied++;
			double x, y;
			map.cellToWorld(cx, cy, x, y);
			double best = std::numeric_limits<double>::infinity();
			for (const auto& obj : o.scene.objects)
				for (const auto& p : obj.parts)
					best = std::min(best, footprintDistance(p, x, y));
			if (best <= 0.10) near++;
		}
	ASSERT_GT(occupied, 500u);
	const double fraction = static_cast<double>(near) / occupied;
	std::cout << "[ MEASURED ] occupied cells within 10 cm of a true obstacle: "
	          << near << "/" << occupied << " = " << fraction << "\n";
	EXPECT_GE(fraction, 0.95);
}

TEST(MapAccuracy, EverySeenDoorAppearsOnceNearItsCentre)
{
	const auto& o = office();
	std::size_t seenDoors = 0;
	for (const auto& obj : o.scene.objects)
	{
		if (obj.label != Label::Door || o.doorPixelsSeen[obj.id] < 150)
			continue;
		seenDoors++;
		const auto& b = std::get<BoxShape>(obj.parts.at(0));
		int matches = 0;
		for (const auto& inst : o.map->instances(Label::Door))
			if (std::hypot(
			        inst.centroid.x - b.center.x,
			        inst.centroid.y - b.center.y) <= 0.3)
				matches++;
		EXPECT_EQ(matches, 1) << "door #" << obj.id << " at (" << b.center.x
		                      << ", " << b.center.y << ")";
	}
	EXPECT_GE(seenDoors, 2u) << "the office trajectory sees both doors";
	EXPECT_EQ(o.map->instances(Label::Door).size(), seenDoors)
	    << "spurious door instances";
}

TEST(MapAccuracy, SavedMapLoadsBack)
{
	const auto& o = office();
	const auto dir = o.dir / "map";
	MapIO::save(*o.map, dir.string());
	SemanticMap back;
	MapIO::load(dir.string(), back);
	EXPECT_EQ(back.geometry(), o.map->geometry());
	EXPECT_EQ(back.instances().size(), o.map->instances().size());
	EXPECT_EQ(back.get("cost"), o.map->get("cost"));
}
