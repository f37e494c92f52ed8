/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <cstdint>
#include <limits>
#include <string>

namespace semnav
{
/** Everything semnav knows about one semantic class: one row of the
 * ClassRegistry (see docs/classes.md). The map, the renderers, travel cost,
 * planning and the scene tools read these fields instead of naming classes.
 * Defaults describe a plain class: drawn nowhere, cost 0, no instances. */
struct ClassInfo
{
	/** An sRGB colour. */
	struct Rgb
	{
		uint8_t r = 255, g = 255, b = 255;
	};

	/** How the map picture (MapRenderer) draws cells of the class. */
	enum class MapStyle : uint8_t
	{
		/** Not drawn (the cell shows its occupancy). */
		None,
		/** Every labelled cell is filled (ground types); where several
		 * area classes meet, the lowest id wins. */
		Area,
		/** The cells of reported instances are filled (objects). */
		Instance
	};

	/** What a cell labelled with the class costs to cross. */
	enum class Passage : uint8_t
	{
		/** Costs nothing (unknown, ceiling: above the robot). */
		Ignored,
		/** A surface with a travel cost (floor, door, grass, stairs). */
		Surface,
		/** Lethal unless the cell has since been seen free (walls,
		 * obstacles, objects standing on the floor). */
		Blocking
	};

	/** Where map instances of the class come from. */
	enum class InstanceSource : uint8_t
	{
		/** The class has no instances (surfaces, walls). */
		None,
		/** Object detections (cascades): an instance is reported once
		 * detected in enough of the sweeps that had it in view. */
		Detections,
		/** Labelled regions of the rule classifier (doors). */
		Regions
	};

	/** How sightings of the class merge into one instance. */
	enum class Merge : uint8_t
	{
		/** Within SemanticMap's object merge distance of one sighting:
		 * small objects side by side stay apart. */
		BySighting,
		/** Within the merge distance of the centroid, or footprints
		 * overlap: large objects seen from several sides. */
		ByFootprint
	};

	/** Sizes (m, z above the floor) outside which a detection or an
	 * instance is implausible. Infinite bounds do not check. */
	struct Plausibility
	{
		/** Detection box width across the view. */
		double minWidth = 0, maxWidth = kInf;
		/** Height of the detection's top above the floor. */
		double minTop = -kInf, maxTop = kInf;
		/** Depth of the detection along the view. */
		double maxDepth = kInf;
		/** An instance's merged vertical extent (doors: no wall
		 * fragments). */
		double minHeight = -kInf;
		/** The lowest point an instance must come down to (stairs start
		 * at the floor). */
		double maxBottom = kInf;
		/** The height an instance's top must reach (washbasins are no side
		 * tables). */
		double minInstanceTop = -kInf;
		/** A wall cell must lie within this distance of the instance's
		 * centroid; 0 = no check. */
		double maxWallDistance = 0;
	};

	static constexpr double kInf = std::numeric_limits<double>::infinity();

	/** Lower-case name used in files, configs and commands, e.g.
	 * "wastebasket". */
	std::string name;
	/** Colour in perception label images (semnav-perceive). */
	Rgb labelColour{90, 90, 90};
	/** Colour in the map picture, and how it is used there. */
	Rgb mapColour{255, 255, 255};
	MapStyle mapStyle = MapStyle::None;

	/** The robot stands on it: points of the class mark free cells (floor,
	 * sidewalk, grass). */
	bool ground = false;
	/** Above the robot (ceiling): never an obstacle hit. */
	bool overhead = false;
	/** Part of the building (ceiling, wall, door): never part of an object
	 * proposal of the detector. */
	bool structure = false;

	Passage passage = Passage::Ignored;
	/** Default travel cost of a Surface in the map's cost layer
	 * (TravelCostModel; the built-ins' config keys override it). */
	double travelCost = 0;
	/** Default u of a Surface for the planner (TraversabilityBuilder's
	 * u_<name>). Blocking classes are blocked there. */
	double plannerCost = 0;
	/** Only a walking robot may cross it (stairs). */
	bool walkingOnly = false;
	/** Rough patches cost more (grass: TravelCostModel's roughness
	 * gain). */
	bool roughnessRaisesCost = false;

	InstanceSource instances = InstanceSource::None;
	Merge merge = Merge::BySighting;
	/** A planner goal by name ("go to the nearest <name>"). */
	bool goal = false;

	/** The class's detector model and 3D shape model (file names in
	 * datasets/cascades); empty when the class is not detected. */
	std::string cascadeFile, shapeModelFile;
	Plausibility plausibility;

	/** True when the class has map instances. */
	bool hasInstances() const { return instances != InstanceSource::None; }
};

}  // namespace semnav
