/* semnav: semantic navigation from tilting-laser sweeps */
// SceneGenerator and `semnav-sim --generate`: generated scenes load, are the
// same bytes for the same seed, hold what the kind promises, and the robot's
// poses and the ways between them are clear of everything on the floor.
#include <gtest/gtest.h>
#include <semnav/common/Error.h>
#include <semnav/sim/SceneGenerator.h>
#include <semnav/sim/SceneLoader.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "../dataset/AppRunner.h"

using semnav::Label;
using semnav::Scene;
using semnav::SceneGenerator;

namespace
{
std::string generate(SceneGenerator::Kind kind, uint64_t seed)
{
	SceneGenerator::TOptions o;
	o.kind = kind;
	o.seed = seed;
	return SceneGenerator(o).generate();
}

/** Distance from (x, y) to a primitive's floor footprint; infinity for
 * primitives starting above 1.2 m (lintels) and for terrain. */
double groundFootprintDistance(
    const semnav::ScenePrimitive& prim, double x, double y)
{
	const auto rectDist = [](double lx, double ly, double hx, double hy)
	{
		const double dx = std::max(std::abs(lx) - hx, 0.0);
		const double dy = std::max(std::abs(ly) - hy, 0.0);
		return std::hypot(dx, dy);
	};
	if (const auto* b = std::get_if<semnav::BoxShape>(&prim))
	{
		if (b->center.z - b->size.z / 2 > 1.2) return INFINITY;
		const double c = std::cos(b->yaw), s = std::sin(b->yaw);
		const double dx = x - b->center.x, dy = y - b->center.y;
		return rectDist(
		    c * dx + s * dy, -s * dx + c * dy, b->size.x / 2, b->size.y / 2);
	}
	if (const auto* cy = std::get_if<semnav::CylinderShape>(&prim))
	{
		if (cy->center.z - cy->height / 2 > 1.2) return INFINITY;
		return std::max(
		    0.0, std::hypot(x - cy->center.x, y - cy->center.y) - cy->radius);
	}
	if (const auto* st = std::get_if<semnav::StairsShape>(&prim))
	{
		const double L = st->steps * st->run;
		const double c = std::cos(st->yaw), s = std::sin(st->yaw);
		const double dx = x - (st->origin.x + c * L / 2);
		const double dy = y - (st->origin.y + s * L / 2);
		return rectDist(
		    c * dx + s * dy, -s * dx + c * dy, L / 2, st->width / 2);
	}
	return INFINITY;
}

double clearance(const Scene& scene, double x, double y)
{
	double d = INFINITY;
	for (const auto& o : scene.objects)
		for (const auto& p : o.parts)
			d = std::min(d, groundFootprintDistance(p, x, y));
	return d;
}

/** Poses >= 0.44 m and the ways between them >= 0.29 m from obstacles
 * (the generator's 0.45 / 0.30, less the file's millimetre rounding). */
void expectTrajectoryFree(const Scene& scene)
{
	ASSERT_GE(scene.trajectory.size(), 5u) << scene.name;
	for (std::size_t i = 0; i < scene.trajectory.size(); i++)
	{
		const auto& p = scene.trajectory[i];
		EXPECT_TRUE(scene.bounds.contains(p.x, p.y)) << scene.name << " " << i;
		EXPECT_GE(clearance(scene, p.x, p.y), 0.44)
		    << scene.name << " pose " << i;
		if (i == 0) continue;
		const auto& q = scene.trajectory[i - 1];
		const double len = std::hypot(p.x - q.x, p.y - q.y);
		const int n = 1 + static_cast<int>(len / 0.05);
		for (int k = 0; k <= n; k++)
		{
			const double t = double(k) / n;
			EXPECT_GE(
			    clearance(scene, q.x + t * (p.x - q.x), q.y + t * (p.y - q.y)),
			    0.29)
			    << scene.name << " way to pose " << i;
		}
	}
}

std::set<Label> labelsOf(const Scene& s)
{
	std::set<Label> l;
	for (const auto& o : s.objects) l.insert(o.label);
	return l;
}

/** Door leaves (all parts of a door object, side by side) 0.8-2.0 m wide. */
void expectDoorWidths(const Scene& s)
{
	for (const auto& o : s.objects)
	{
		if (o.label != Label::Door) continue;
		double w = 0;
		for (const auto& p : o.parts)
		{
			const auto& b = std::get<semnav::BoxShape>(p);
			w += std::max(b.size.x, b.size.y);
		}
		EXPECT_GE(w, 0.8 - 1e-3) << s.name << " object " << o.id;
		EXPECT_LE(w, 2.0 + 1e-3) << s.name << " object " << o.id;
	}
}
}  // namespace

TEST(SceneGenerator, IndoorScenesLoadRepeatAndAreFree)
{
	std::set<Label> seen;
	std::set<std::string> texts;
	for (const uint64_t seed : {1, 2, 3, 1000})
	{
		const std::string a = generate(SceneGenerator::Kind::Indoor, seed);
		EXPECT_EQ(a, generate(SceneGenerator::Kind::Indoor, seed)) << seed;
		texts.insert(a);
		const Scene s = semnav::SceneLoader::parse(a, "indoor.yaml");
		EXPECT_EQ(s.name, "indoor_" + std::to_string(seed));
		EXPECT_TRUE(s.ceilingHeight.has_value());
		expectTrajectoryFree(s);
		expectDoorWidths(s);
		const auto l = labelsOf(s);
		EXPECT_TRUE(l.count(Label::Door)) << seed;
		seen.insert(l.begin(), l.end());
	}
	EXPECT_EQ(texts.size(), 4u) << "different seeds, different buildings";
	for (const Label l :
	     {Label::Wall, Label::Washbasin, Label::Wastebasket, Label::Stairs,
	      Label::Obstacle})
		EXPECT_TRUE(seen.count(l)) << semnav::labelName(l);
}

TEST(SceneGenerator, PlantPotsCarryFoliageWiderThanThePot)
{
	// A pot of a wastebasket's size (a cylinder standing on the floor, top
	// <= 0.6 m) labelled obstacle always has a plant above it: a cylinder of
	// the same object, wider than the pot, starting at or above its top (the
	// file rounds to 1 mm).
	int pots = 0;
	for (uint64_t seed = 0; seed < 30; seed++)
	{
		const Scene s = semnav::SceneLoader::parse(
		    generate(SceneGenerator::Kind::Indoor, seed), "indoor.yaml");
		for (const auto& o : s.objects)
		{
			if (o.label != Label::Obstacle) continue;
			const auto* pot =
			    std::get_if<semnav::CylinderShape>(&o.parts.front());
			if (!pot || pot->center.z - pot->height / 2 > 0.01 ||
			    pot->center.z + pot->height / 2 > 0.6)
				continue;
			pots++;
			const double potTop = pot->center.z + pot->height / 2;
			bool foliage = false;
			for (const auto& p : o.parts)
				if (const auto* c = std::get_if<semnav::CylinderShape>(&p))
					foliage |= c->radius >= 1.5 * pot->radius - 2e-3 &&
					           c->center.z - c->height / 2 >= potTop - 2e-3;
			EXPECT_TRUE(foliage) << s.name << " object " << o.id;
		}
	}
	EXPECT_GT(pots, 5) << "the buildings have plant pots";
}

TEST(SceneGenerator, OutdoorScenesLoadRepeatAndAreFree)
{
	std::set<Label> seen;
	for (const uint64_t seed : {1, 2, 1000})
	{
		const std::string a = generate(SceneGenerator::Kind::Outdoor, seed);
		EXPECT_EQ(a, generate(SceneGenerator::Kind::Outdoor, seed)) << seed;
		const Scene s = semnav::SceneLoader::parse(a, "outdoor.yaml");
		EXPECT_FALSE(s.ceilingHeight.has_value());
		expectTrajectoryFree(s);
		expectDoorWidths(s);
		const auto l = labelsOf(s);
		for (const Label k :
		     {Label::Sidewalk, Label::Grass, Label::Door, Label::Wastebasket,
		      Label::Obstacle})
			EXPECT_TRUE(l.count(k)) << seed << " " << semnav::labelName(k);
		seen.insert(l.begin(), l.end());
	}
	EXPECT_FALSE(seen.count(Label::Ceiling));
}

TEST(SceneGenerator, KindNames)
{
	EXPECT_EQ(
	    SceneGenerator::kindFromName("outdoor"), SceneGenerator::Kind::Outdoor);
	EXPECT_THROW(SceneGenerator::kindFromName("Indoor"), semnav::Error);
}

TEST(SemnavSimGenerate, WritesTheGeneratorsBytes)
{
	namespace fs = std::filesystem;
	const fs::path out = fs::temp_directory_path() /
	                     ("semnav_gen_" + std::to_string(::getpid()) + ".yaml");
	const auto r = semnav::test::runApp(
	    "semnav-sim", "--generate outdoor --seed 7 --out " + out.string());
	ASSERT_EQ(r.code, 0) << r.err;
	std::ifstream f(out);
	std::stringstream text;
	text << f.rdbuf();
	EXPECT_EQ(text.str(), generate(SceneGenerator::Kind::Outdoor, 7));
	fs::remove(out);
}

TEST(SemnavSimGenerate, BadArgumentsAreOneLineAndExitTwo)
{
	for (const std::string args :
	     {"--generate castle --seed 1 --out /tmp/x.yaml",
	      "--generate indoor --seed 1", "--generate indoor --seed x --out a",
	      "--generate indoor --scene a.yaml --out /tmp/x.yaml"})
	{
		const auto r = semnav::test::runApp("semnav-sim", args);
		EXPECT_EQ(r.code, 2) << args;
		EXPECT_EQ(semnav::test::lineCount(r.err), 1u) << args << ": " << r.err;
		EXPECT_EQ(r.err.rfind("semnav-sim: ", 0), 0u) << r.err;
	}
}
