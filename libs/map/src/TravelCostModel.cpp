/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/config/CConfigFileBase.h>
#include <semnav/common/ClassRegistry.h>
#include <semnav/common/Error.h>
#include <semnav/common/OptionTable.h>
#include <semnav/map/TravelCostModel.h>

#include <algorithm>
#include <cmath>

namespace semnav
{
namespace
{
using O = TravelCostModel::TOptions;
const OptionTable<O>& optionTable()
{
	static const auto t =
	    OptionTable<O>()
	        .real(
	            "lethal_cost", &O::lethalCost, 1, 1e9,
	            "Cost of a blocked cell (the paper's L).")
	        .real("floor_cost", &O::floorCost, 0, &O::lethalCost, "Floor.")
	        .real("door_cost", &O::doorCost, 0, &O::lethalCost, "Door.")
	        .real(
	            "sidewalk_cost", &O::sidewalkCost, 0, &O::lethalCost,
	            "Sidewalk.")
	        .real(
	            "grass_cost", &O::grassCost, 0, &O::lethalCost,
	            "Grass: grass_cost + grass_roughness_gain * (1 - R-bar).")
	        .real(
	            "grass_roughness_gain", &O::grassRoughnessGain, 0,
	            &O::lethalCost, "See grass_cost.")
	        .real(
	            "stairs_cost", &O::stairsCost, 0, &O::lethalCost,
	            "Stairs: passable at this cost for a walking robot only.")
	        .choice(
	            "robot_type", &O::robotType,
	            {{TravelCostModel::RobotType::Wheeled, "wheeled"},
	             {TravelCostModel::RobotType::Walking, "walking"}},
	            "wheeled | walking.")
	        .real(
	            "unknown_cost", &O::unknownCost, 0, &O::lethalCost,
	            "Cost of a cell never observed.");
	return t;
}
}  // namespace

SEMNAV_OPTIONS_FROM_TABLE(TravelCostModel::TOptions, optionTable())

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
