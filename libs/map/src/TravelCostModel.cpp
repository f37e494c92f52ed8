/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/config/CConfigFileBase.h>
#include <semnav/common/ClassRegistry.h>
#include <semnav/common/ConfigChecks.h>
#include <semnav/common/Error.h>
#include <semnav/map/TravelCostModel.h>

#include <algorithm>
#include <cmath>

namespace semnav
{
void TravelCostModel::TOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& c, const std::string& s)
{
	checkKnownKeys(
	    c, s,
	    {"lethal_cost", "floor_cost", "door_cost", "sidewalk_cost",
	     "grass_cost", "grass_roughness_gain", "stairs_cost", "robot_type",
	     "unknown_cost"});
	lethalCost = readChecked(c, s, "lethal_cost", lethalCost, 1, 1e9);
	floorCost = readChecked(c, s, "floor_cost", floorCost, 0, lethalCost);
	doorCost = readChecked(c, s, "door_cost", doorCost, 0, lethalCost);
	sidewalkCost =
	    readChecked(c, s, "sidewalk_cost", sidewalkCost, 0, lethalCost);
	grassCost = readChecked(c, s, "grass_cost", grassCost, 0, lethalCost);
	grassRoughnessGain = readChecked(
	    c, s, "grass_roughness_gain", grassRoughnessGain, 0, lethalCost);
	stairsCost = readChecked(c, s, "stairs_cost", stairsCost, 0, lethalCost);
	unknownCost = readChecked(c, s, "unknown_cost", unknownCost, 0, lethalCost);
	const std::string type = c.read_string(
	    s, "robot_type",
	    robotType == RobotType::Walking ? "walking" : "wheeled");
	if (type == "wheeled")
		robotType = RobotType::Wheeled;
	else if (type == "walking")
		robotType = RobotType::Walking;
	else
		throw ConfigError(
		    "[" + s + "] robot_type = '" + type +
		    "' is not 'wheeled' or 'walking'");
}

void TravelCostModel::TOptions::saveToConfigFile(
    mrpt::config::CConfigFileBase& c, const std::string& s) const
{
	c.write(s, "lethal_cost", lethalCost);
	c.write(s, "floor_cost", floorCost);
	c.write(s, "door_cost", doorCost);
	c.write(s, "sidewalk_cost", sidewalkCost);
	c.write(s, "grass_cost", grassCost);
	c.write(s, "grass_roughness_gain", grassRoughnessGain);
	c.write(s, "stairs_cost", stairsCost);
	c.write(
	    s, "robot_type",
	    robotType == RobotType::Walking ? "walking" : "wheeled");
	c.write(s, "unknown_cost", unknownCost);
}

TravelCostModel::TravelCostModel() : TravelCostModel(TOptions()) {}
TravelCostModel::TravelCostModel(const TOptions& o) : m_options(o) {}

double TravelCostModel::surfaceCost(Label l) const
{
	const auto& o = m_options;
	switch (l)
	{
		case Label::Floor:
			return o.floorCost;
		case Label::Door:
			return o.doorCost;
		case Label::Sidewalk:
			return o.sidewalkCost;
		case Label::Grass:
			return o.grassCost;
		case Label::Stairs:
			return o.stairsCost;
		default:
			return classInfo(l).travelCost;
	}
}

double TravelCostModel::labelCost(
    Label l, double roughness, double obstacleCost) const
{
	const auto& o = m_options;
	const ClassInfo& c = classInfo(l);
	switch (c.passage)
	{
		case ClassInfo::Passage::Blocking:
			return obstacleCost;
		case ClassInfo::Passage::Surface:
			break;
		default:
			return 0;
	}
	if (c.walkingOnly && o.robotType != RobotType::Walking) return o.lethalCost;
	double u = surfaceCost(l);
	if (c.roughnessRaisesCost && !std::isnan(roughness))
		u += o.grassRoughnessGain * std::max(0.0, 1.0 - roughness);
	return u;
}

double TravelCostModel::cost(
    LabelSet labels, double roughness, Occupancy occupancy) const
{
	const auto& o = m_options;
	if (occupancy == Occupancy::Occupied) return o.lethalCost;
	if (labels.empty())
		return occupancy == Occupancy::Unknown ? o.unknownCost : o.floorCost;
	const double obstacleCost =
	    occupancy == Occupancy::Free ? 0.0 : o.lethalCost;
	double u = 0;
	for (Label l : allLabels())
		if (labels.contains(l))
			u = std::max(u, labelCost(l, roughness, obstacleCost));
	return std::min(u, o.lethalCost);
}

}  // namespace semnav
