/* semnav: semantic navigation from tilting-laser sweeps */
// Mapping with true poses on simulated scenes: occupied cells lie on real
// obstacles; doors, washbasins, wastebaskets and stairs appear once near their
// true centres.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFile.h>
#include <semnav/common/ConfigChecks.h>
#include <semnav/detection/SweepPerception.h>
#include <semnav/map/MapIO.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/perception/PerceptionPipeline.h>
#include <semnav/scan/GroundTruthLog.h>
#include <semnav/scan/RawlogSweepReader.h>
#include <semnav/sim/SceneLoader.h>
#include <semnav/sim/SimulationRunner.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
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

/** The true centre (x, y) of an object: its first part's footprint
 * centre (a washbasin's basin, a staircase's flight). */
mrpt::math::TPoint2D trueCentre(const SceneObject& obj)
{
	const auto& p = obj.parts.at(0);
	if (const auto* b = std::get_if<BoxShape>(&p))
		return {b->center.x, b->center.y};
	if (const auto* c = std::get_if<CylinderShape>(&p))
		return {c->center.x, c->center.y};
	const auto& st = std::get<StairsShape>(p);
	const double len = st.steps * st.run;
	return {
	    st.origin.x + std::cos(st.yaw) * len / 2,
	    st.origin.y + std::sin(st.yaw) * len / 2};
}

struct MappedScene
{
	Scene scene;
	fs::path dir;
	std::string yamlPath;
	std::unique_ptr<SemanticMap> map;
	/** Per scene object id: sweeps that saw >= 150 of its pixels (the
	 * detection rule of issue 4). */
	std::vector<int> sweepsSeen;
};

/** Simulates a scene (seed 1), perceives every sweep with the shipped
 * rules and cascades, maps it at the true poses. */
MappedScene mapScene(const std::string& yaml)
{
	MappedScene o;
	o.yamlPath = std::string(SEMNAV_SOURCE_DIR) + yaml;
	o.scene = SceneLoader::loadFile(o.yamlPath);
	o.dir = fs::temp_directory_path() / ("semnav_mapacc_" + o.scene.name + "_" +
	                                     std::to_string(::getpid()));
	fs::remove_all(o.dir);
	const auto res = SimulationRunner(o.scene, SimulationRunner::TOptions(), 1)
	                     .run(o.dir.string());
	const auto gt = GroundTruthLog::forRawlog(o.dir.string(), res.rawlogPath);
	// The shipped map configuration.
	SemanticMap::TOptions mapOpts;
	const auto cfg = openIniFile(
	    std::string(SEMNAV_SOURCE_DIR) + "/config/map.ini",
	    {"SemanticMap", "TravelCost", "SweepAssembler"});
	mapOpts.loadFromConfigFile(*cfg, "SemanticMap");
	mapOpts.cost.loadFromConfigFile(*cfg, "TravelCost");
	o.map = std::make_unique<SemanticMap>(mapOpts);
	SweepPerception perception(
	    PerceptionPipeline::TOptions(),
	    CascadeDetector::TOptions::fromIniFile(
	        std::string(SEMNAV_SOURCE_DIR) + "/config/cascade.ini"));
	RawlogSweepReader reader(res.rawlogPath);
	o.sweepsSeen.assign(o.scene.objects.size() + 1, 0);
	Sweep s;
	while (reader.next(s))
	{
		o.map->insert(s, perception.process(s), gt.pose(s.index()));
		const cv::Mat lab =
		    cv::imread(gt.labelImagePath(s.index()), cv::IMREAD_UNCHANGED);
		std::vector<int> count(o.scene.objects.size() + 1, 0);
		for (int r = 0; r < lab.rows; r++)
			for (int c = 0; c < lab.cols; c++)
				count[lab.at<uint16_t>(r, c) >> 8]++;
		for (std::size_t i = 1; i < count.size(); i++)
			o.sweepsSeen[i] += count[i] >= 150;
	}
	return o;
}

/** The comment line above an object in its scene file ("# table"). */
std::string objectComment(const MappedScene& o, const SceneObject& obj)
{
	std::ifstream in(o.yamlPath);
	std::string line, prev;
	for (int n = 1; std::getline(in, line); n++)
	{
		if (n == obj.line) return prev;
		prev = line;
	}
	return "";
}

/** Diagnostic (SEMNAV_MAP_DIAG set): every instance of `labels`, reported
 * or not, with its nearest true object of any label. */
void printInstances(const MappedScene& o, const std::vector<Label>& labels)
{
	if (!std::getenv("SEMNAV_MAP_DIAG")) return;
	for (const auto& inst : o.map->allInstances())
	{
		if (std::find(labels.begin(), labels.end(), inst.label) == labels.end())
			continue;
		const SceneObject* nearest = nullptr;
		double best = std::numeric_limits<double>::infinity();
		for (const auto& obj : o.scene.objects)
			for (const auto& p : obj.parts)
			{
				const double d =
				    footprintDistance(p, inst.centroid.x, inst.centroid.y);
				if (d < best)
				{
					best = d;
					nearest = &obj;
				}
			}
		double sameLabel = std::numeric_limits<double>::infinity();
		for (const auto& obj : o.scene.objects)
			if (obj.label == inst.label)
			{
				const auto c = trueCentre(obj);
				sameLabel = std::min(
				    sameLabel,
				    std::hypot(inst.centroid.x - c.x, inst.centroid.y - c.y));
			}
		std::cout << "  DIAG " << o.scene.name << " " << labelName(inst.label)
		          << " #" << inst.id
		          << (o.map->reported(inst) ? " REPORTED" : " dropped")
		          << " at (" << inst.centroid.x << ", " << inst.centroid.y
		          << ", " << inst.centroid.z << ") " << inst.observations << "/"
		          << inst.views << " shape " << inst.bestShapeScore << " ext ("
		          << inst.extent().x << ", " << inst.extent().y << ", "
		          << inst.extent().z << ") z " << inst.minCorner.z << ".."
		          << inst.maxCorner.z << " true-same-label " << sameLabel
		          << " m; nearest "
		          << (nearest ? labelName(nearest->label) : "-") << " #"
		          << (nearest ? nearest->id : 0) << " "
		          << (nearest ? objectComment(o, *nearest) : "") << " at "
		          << best << " m\n";
		for (const auto& s : inst.sightings)
			std::cout << "      sighting (" << s.x << ", " << s.y << ", " << s.z
			          << ")\n";
	}
}

/** Diagnostic (SEMNAV_MAP_DIAG set): the grid around every staircase. */
void printStairs(const MappedScene& o)
{
	if (!std::getenv("SEMNAV_MAP_DIAG")) return;
	const auto& map = *o.map;
	for (const auto& obj : o.scene.objects)
	{
		if (obj.label != Label::Stairs) continue;
		const auto c = trueCentre(obj);
		std::cout << "  STAIRS " << o.scene.name << " #" << obj.id << " ("
		          << c.x << ", " << c.y << ")\n";
		for (double y = c.y + 2.5; y >= c.y - 2.5; y -= 0.05)
		{
			std::string line;
			for (double x = c.x - 2.5; x <= c.x + 2.5; x += 0.05)
			{
				int cx, cy;
				if (!map.worldToCell(x, y, cx, cy))
				{
					line += '?';
					continue;
				}
				const bool in = footprintDistance(obj.parts[0], x, y) <= 0;
				const auto ls = map.labels(cx, cy);
				const auto st = map.cellState(cx, cy);
				char ch = ' ';
				if (ls.contains(Label::Stairs))
					ch = 's';
				else if (ls.contains(Label::Wall))
					ch = 'w';
				else if (st == SemanticMap::CellState::Occupied)
					ch = '#';
				else if (st == SemanticMap::CellState::Free)
					ch = '.';
				if (in)
					ch = ch == ' ' ? '_' : ch == '.' ? 'o' : std::toupper(ch);
				line += ch;
			}
			std::cout << "    " << line << "\n";
		}
	}
}

const MappedScene& office()
{
	static const MappedScene m = mapScene("/datasets/office/office.yaml");
	return m;
}

struct ObjectScore
{
	std::size_t seen = 0, foundOnce = 0, instances = 0, spurious = 0;
};

/** Objects of `labels` seen by as many sweeps as the map needs to report
 * them (min_observations; >= 150 pixels make a sweep see it, the detection
 * rule of issue 4) and found once within 0.3 m of their true centre;
 * instances of those labels further than 0.3 m from every true object of
 * their label (spurious). Prints every failure. */
ObjectScore scoreObjects(const MappedScene& o, const std::vector<Label>& labels)
{
	ObjectScore score;
	printInstances(o, labels);
	printStairs(o);
	const auto& opts = o.map->options();
	for (const Label l : labels)
	{
		const int needed =
		    l == Label::Door ? opts.doorMinObservations : opts.minObservations;
		const auto inst = o.map->instances(l);
		std::vector<bool> explained(inst.size(), false);
		std::size_t seen = 0;
		for (const auto& obj : o.scene.objects)
		{
			if (obj.label != l) continue;
			const auto c = trueCentre(obj);
			int matches = 0;
			for (std::size_t k = 0; k < inst.size(); k++)
				if (std::hypot(
				        inst[k].centroid.x - c.x, inst[k].centroid.y - c.y) <=
				    0.3)
				{
					matches++;
					explained[k] = true;
				}
			if (o.sweepsSeen[obj.id] < needed) continue;
			seen++;
			if (matches == 1)
				score.foundOnce++;
			else
				std::cout << "  " << o.scene.name << ": " << labelName(l)
				          << " #" << obj.id << " at (" << c.x << ", " << c.y
				          << "), seen by " << o.sweepsSeen[obj.id]
				          << " sweeps, has " << matches
				          << " instances within 0.3 m\n";
		}
		for (std::size_t k = 0; k < inst.size(); k++)
			if (!explained[k])
			{
				score.spurious++;
				std::cout << "  " << o.scene.name << ": spurious "
				          << labelName(l) << " #" << inst[k].id << " at ("
				          << inst[k].centroid.x << ", " << inst[k].centroid.y
				          << "), detected " << inst[k].observations << "x in "
				          << inst[k].views << " views\n";
			}
		std::cout << "[ MEASURED ] " << o.scene.name << " " << labelName(l)
		          << ": " << seen << " seen, " << inst.size() << " instances\n";
		score.seen += seen;
		score.instances += inst.size();
	}
	return score;
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

TEST(MapAccuracy, OfficeObjectsAppearOnceNearTheirCentres)
{
	const auto& o = office();
	const auto s = scoreObjects(
	    o, {Label::Door, Label::Washbasin, Label::Wastebasket, Label::Stairs});
	// README "Objects in the map": 6 seen, 6 found once, 0 spurious
	// (measured, the same on every run); asserted exactly.
	EXPECT_EQ(s.seen, 6u);
	EXPECT_EQ(s.foundOnce, s.seen);
	EXPECT_EQ(s.spurious, 0u);
	EXPECT_EQ(o.map->instances(Label::Door).size(), 2u)
	    << "the office trajectory sees both doors";
	EXPECT_EQ(o.map->instances(Label::Wastebasket).size(), 2u)
	    << "the office trajectory looks at wastebaskets 2 and 3";
}

/** Maps the cascade scenes `names` (datasets/cascade-scenes) and sums their
 * washbasin, wastebasket and stairs scores. */
ObjectScore scoreCascadeScenes(const std::vector<std::string>& names)
{
	ObjectScore all;
	for (const auto& name : names)
	{
		const auto o = mapScene("/datasets/cascade-scenes/" + name + ".yaml");
		const auto s = scoreObjects(
		    o, {Label::Washbasin, Label::Wastebasket, Label::Stairs});
		all.seen += s.seen;
		all.foundOnce += s.foundOnce;
		all.instances += s.instances;
		all.spurious += s.spurious;
		fs::remove_all(o.dir);
	}
	std::cout << "[ MEASURED ] " << names.front() << ".." << names.back()
	          << ": " << all.foundOnce << " of " << all.seen
	          << " seen objects found once within 0.3 m, " << all.spurious
	          << " spurious of " << all.instances << " instances\n";
	return all;
}

TEST(MapAccuracy, HeldOutSceneObjects)
{
	// The cascade test scenes (not used in training); README "Objects in
	// the map". Measured (the same on every run) with
	// ctest -R MapAccuracy.HeldOut -V: 50 seen, 50 found once, 0 spurious.
	// Asserts at most one object fewer and one spurious instance.
	const auto all = scoreCascadeScenes(
	    {"test_a", "test_b", "test_c", "test_d", "test_e", "test_f"});
	ASSERT_GE(all.seen, 49u);
	EXPECT_GE(all.foundOnce, 49u);
	EXPECT_LE(all.spurious, 1u);
}

TEST(MapAccuracy, ValidationSceneObjects)
{
	// The cascade validation scenes (neither trained on nor held out), so
	// that map-level rules are not tuned to the held-out scenes alone.
	// Measured (the same on every run) with
	// ctest -R MapAccuracy.Validation -V: 54 seen, 53 found once (val_b's
	// corner wastebasket, seen by one sweep, is not), 0 spurious. Asserts
	// at most one object fewer and one spurious instance.
	const auto all = scoreCascadeScenes(
	    {"val_a", "val_b", "val_c", "val_d", "val_e", "val_f"});
	ASSERT_GE(all.seen, 53u);
	EXPECT_GE(all.foundOnce, 52u);
	EXPECT_LE(all.spurious, 1u);
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

TEST(MapAccuracy, DISABLED_TrainingSceneObjects)
{
	// The cascade training scenes, for diagnosing map rules on more objects
	// than the held-out and validation scenes hold (run with
	// --gtest_also_run_disabled_tests; SEMNAV_MAP_DIAG=1 prints every
	// instance; minutes, so not in every ctest run). README "Objects in
	// the map", measured with --gtest_also_run_disabled_tests
	// --gtest_filter='*Training*': 177 seen, 177 found once, 1 spurious (of
	// 179 instances). Asserts at most one object fewer and one more
	// spurious instance.
	std::vector<std::string> names;
	for (char c = 'a'; c <= 't'; c++)
		names.push_back(std::string("train_") + c);
	const auto all = scoreCascadeScenes(names);
	ASSERT_GE(all.seen, 176u);
	EXPECT_GE(all.foundOnce, 176u);
	EXPECT_LE(all.spurious, 2u);
}
