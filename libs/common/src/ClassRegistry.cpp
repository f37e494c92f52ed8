/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/ClassRegistry.h>
#include <semnav/common/Error.h>

#include <algorithm>
#include <cctype>

namespace semnav
{
namespace
{
using MapStyle = ClassInfo::MapStyle;
using Passage = ClassInfo::Passage;
using Source = ClassInfo::InstanceSource;
using Merge = ClassInfo::Merge;

ClassInfo row(const char* name, ClassInfo::Rgb labelColour)
{
	ClassInfo c;
	c.name = name;
	c.labelColour = labelColour;
	return c;
}

ClassInfo drawn(ClassInfo c, ClassInfo::Rgb colour, MapStyle style)
{
	c.mapColour = colour;
	c.mapStyle = style;
	return c;
}

ClassInfo surface(ClassInfo c, double travelCost, double plannerCost)
{
	c.passage = Passage::Surface;
	c.travelCost = travelCost;
	c.plannerCost = plannerCost;
	return c;
}

ClassInfo blocking(ClassInfo c)
{
	c.passage = Passage::Blocking;
	return c;
}

/** An object class with instances, a goal of the planner. */
ClassInfo object(ClassInfo c, Source source, Merge merge)
{
	c.instances = source;
	c.merge = merge;
	c.goal = true;
	return c;
}

/** A class found by a cascade and checked by a shape model. */
ClassInfo detected(
    ClassInfo c, double minWidth, double maxWidth, double minTop, double maxTop,
    double maxDepth)
{
	c.cascadeFile = c.name + ".xml";
	c.shapeModelFile = c.name + "-shape.xml.gz";
	auto& p = c.plausibility;
	p.minWidth = minWidth;
	p.maxWidth = maxWidth;
	p.minTop = minTop;
	p.maxTop = maxTop;
	p.maxDepth = maxDepth;
	return c;
}

/** The built-in classes in id order (Label's values). */
std::vector<ClassInfo> builtInClasses()
{
	const ClassInfo::Rgb black{0, 0, 0};
	std::vector<ClassInfo> t;
	t.push_back(row("unknown", {90, 90, 90}));
	ClassInfo floor = surface(row("floor", {40, 110, 255}), 0, 0);
	floor.ground = true;
	t.push_back(floor);
	ClassInfo ceiling = row("ceiling", {255, 220, 0});
	ceiling.mapColour = {255, 230, 200};
	ceiling.overhead = true;
	ceiling.structure = true;
	t.push_back(ceiling);
	ClassInfo wall = drawn(blocking(row("wall", {220, 30, 30})), black, {});
	wall.structure = true;
	t.push_back(wall);
	ClassInfo door = object(
	    drawn(
	        surface(row("door", {140, 70, 10}), 0, 0), {255, 140, 0},
	        MapStyle::Instance),
	    Source::Regions, Merge::ByFootprint);
	// Seen close, a door's top is above the tilt range: 0.64-1.07 m of it.
	door.plausibility.minHeight = 0.6;
	door.structure = true;
	t.push_back(door);
	ClassInfo sidewalk = drawn(
	    surface(row("sidewalk", {200, 200, 200}), 0.2, 0), {190, 190, 190},
	    MapStyle::Area);
	sidewalk.ground = true;
	t.push_back(sidewalk);
	ClassInfo grass = drawn(
	    surface(row("grass", {20, 170, 20}), 1.0, 0.05), {120, 220, 120},
	    MapStyle::Area);
	grass.ground = true;
	grass.roughnessRaisesCost = true;
	t.push_back(grass);
	ClassInfo stairs = detected(
	    object(
	        drawn(
	            surface(row("stairs", {255, 140, 0}), 2.0, 0.1), {200, 0, 200},
	            MapStyle::Instance),
	        Source::Detections, Merge::ByFootprint),
	    0.6, 2.2, 0.25, 2.0, 2.5);
	stairs.walkingOnly = true;
	stairs.plausibility.maxBottom = 0.1;
	t.push_back(stairs);
	ClassInfo washbasin = detected(
	    object(
	        drawn(
	            blocking(row("washbasin", {0, 220, 220})), {0, 128, 255},
	            MapStyle::Instance),
	        Source::Detections, Merge::BySighting),
	    0.25, 0.9, 0.6, 1.1, 0.6);
	washbasin.plausibility.minInstanceTop = 0.75;
	washbasin.plausibility.maxWallDistance = 0.6;
	t.push_back(washbasin);
	t.push_back(detected(
	    object(
	        drawn(
	            blocking(row("wastebasket", {255, 0, 255})), {0, 180, 0},
	            MapStyle::Instance),
	        Source::Detections, Merge::BySighting),
	    0.12, 0.55, 0.2, 0.65, 0.45));
	t.push_back(drawn(blocking(row("obstacle", {140, 40, 210})), black, {}));
	return t;
}

bool isLowerCaseName(const std::string& s)
{
	return !s.empty() && std::all_of(
	                         s.begin(), s.end(),
	                         [](unsigned char ch) {
		                         return std::islower(ch) || std::isdigit(ch) ||
		                                ch == '_' || ch == '-';
	                         });
}
}  // namespace

ClassRegistry& ClassRegistry::instance()
{
	static ClassRegistry registry;
	return registry;
}

ClassRegistry::ClassRegistry()
{
	resetToBuiltIns();
}

void ClassRegistry::resetToBuiltIns()
{
	m_rows.clear();
	m_labels.clear();
	for (auto& c : builtInClasses()) add(std::move(c));
}

Label ClassRegistry::add(ClassInfo info)
{
	if (!isLowerCaseName(info.name))
		throw Error(
		    "class name '" + info.name +
		    "' must be lower case letters, digits, '_' or '-'");
	if (find(info.name))
		throw Error("class '" + info.name + "' is already registered");
	if (m_rows.size() >= kMaxLabelCount)
		throw Error(
		    "cannot register class '" + info.name + "': the registry holds " +
		    std::to_string(kMaxLabelCount) + " classes at most");
	const Label l = static_cast<Label>(m_rows.size());
	m_rows.push_back(std::move(info));
	m_labels.push_back(l);
	return l;
}

bool ClassRegistry::contains(Label l) const
{
	return static_cast<std::size_t>(l) < m_rows.size();
}

const ClassInfo& ClassRegistry::info(Label l) const
{
	if (!contains(l)) labelFromId(static_cast<unsigned>(l));  // throws
	return m_rows[static_cast<std::size_t>(l)];
}

std::optional<Label> ClassRegistry::find(const std::string& name) const
{
	for (std::size_t i = 0; i < m_rows.size(); i++)
		if (m_rows[i].name == name) return static_cast<Label>(i);
	return std::nullopt;
}

const ClassInfo& classInfo(Label l)
{
	return ClassRegistry::instance().info(l);
}

}  // namespace semnav
