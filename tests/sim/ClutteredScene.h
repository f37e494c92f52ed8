/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once
// Test scenes built in code, shared by the simulator's tests and bench_sim.
#include <semnav/sim/Scene.h>

#include <cmath>
#include <random>
#include <utility>

namespace semnav::test
{
/** A scene object with one primitive. */
inline SceneObject sceneObject(Label l, int id, ScenePrimitive p)
{
	SceneObject o;
	o.label = l;
	o.id = id;
	o.parts.push_back(std::move(p));
	return o;
}

/** Office-like room, 12 x 8 m: 4 walls, a door, 13 boxes, 8 cylinders, 2
 * stairs, 2 rough terrain patches (30 objects; random sizes, seed 7). */
inline Scene clutteredScene()
{
	Scene s;
	s.name = "cluttered";
	s.bounds = {0, 0, 12, 8};
	s.ceilingHeight = 2.7;
	int id = 0;
	auto add = [&](Label l, ScenePrimitive p)
	{ s.objects.push_back(sceneObject(l, ++id, std::move(p))); };
	add(Label::Wall, BoxShape{{6, 0.05, 1.35}, {12, 0.1, 2.7}, 0});
	add(Label::Wall, BoxShape{{6, 7.95, 1.35}, {12, 0.1, 2.7}, 0});
	add(Label::Wall, BoxShape{{0.05, 4, 1.35}, {0.1, 8, 2.7}, 0});
	add(Label::Wall, BoxShape{{11.95, 4, 1.35}, {0.1, 8, 2.7}, 0});
	add(Label::Door, BoxShape{{3, 7.88, 1.0}, {0.9, 0.04, 2.0}, 0});
	std::mt19937_64 rng(7);
	std::uniform_real_distribution<double> u(0, 1);
	// (Braced lists are evaluated left to right: the same scene with every
	// compiler.)
	for (int k = 0; k < 13; k++)
		add(Label::Obstacle,
		    BoxShape{
		        {1 + 10 * u(rng), 1 + 6 * u(rng), 0.3 + u(rng)},
		        {0.2 + u(rng), 0.2 + u(rng), 0.3 + u(rng)},
		        2 * M_PI * u(rng)});
	for (int k = 0; k < 8; k++)
	{
		CylinderShape c;
		c.center = {1 + 10 * u(rng), 1 + 6 * u(rng), 0.5 * u(rng) + 0.2};
		c.radius = 0.05 + 0.3 * u(rng);
		c.height = 0.2 + u(rng);
		add(Label::Wastebasket, c);
	}
	StairsShape st;
	st.origin = {8, 4};
	st.yaw = M_PI / 2;
	st.steps = 5;
	st.rise = 0.17;
	st.run = 0.28;
	st.width = 1.2;
	add(Label::Stairs, st);
	st.origin = {2, 2};
	st.yaw = 0.3;
	add(Label::Stairs, st);
	add(Label::Grass,
	    TerrainShape{{{0.5, 0.5}, {4, 0.5}, {4, 3}, {0.5, 3}}, 0.03});
	add(Label::Sidewalk, TerrainShape{{{6, 5}, {11, 5.5}, {9, 7.5}}, 0.05});
	return s;
}

}  // namespace semnav::test
