/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <semnav/common/ClassRegistry.h>
#include <semnav/common/LabelSet.h>

#include <string>

namespace semnav
{
/** Travel cost u of a map cell from what was seen in it (paper sec. 3:
 * "u = 0 for the floor, u = L for a wall"): the most expensive of its
 * labels, each priced by its ClassRegistry row (ClassInfo::passage): rough
 * classes (grass) made dearer by their roughness (u grows as R-bar falls
 * below 1), walking-only classes (stairs) passable only for a walking
 * robot, L for blocking classes. Default costs come from the registry; the
 * options override the built-in surfaces. */
class TravelCostModel
{
public:
	enum class RobotType
	{
		Wheeled,
		Walking
	};

	struct TOptions : public mrpt::config::CLoadableOptions
	{
		void loadFromConfigFile(
		    const mrpt::config::CConfigFileBase& c,
		    const std::string& section) override;
		void saveToConfigFile(
		    mrpt::config::CConfigFileBase& c,
		    const std::string& section) const override;

		/** Cost of a blocked cell (the paper's L). */
		double lethalCost = 1000;
		double floorCost = classInfo(Label::Floor).travelCost;
		double doorCost = classInfo(Label::Door).travelCost;
		double sidewalkCost = classInfo(Label::Sidewalk).travelCost;
		/** Grass: grassCost + grassRoughnessGain * (1 - R-bar). */
		double grassCost = classInfo(Label::Grass).travelCost;
		double grassRoughnessGain = 20.0;
		/** Stairs for a walking robot; a wheeled one cannot use them. */
		double stairsCost = classInfo(Label::Stairs).travelCost;
		RobotType robotType = RobotType::Wheeled;
		/** Cost of a cell never observed. */
		double unknownCost = 1000;
	};

	TravelCostModel();
	explicit TravelCostModel(const TOptions& o);

	/** What the occupancy grid says of a cell. */
	enum class Occupancy
	{
		Unknown,
		Free,
		Occupied
	};

	/** u of a cell with these labels; `roughness` is its mean R-bar (NaN if
	 * none). Occupied cells cost L; blocking labels (wall, obstacle,
	 * washbasin, wastebasket) cost L unless the cell has since been seen
	 * free (the object left); an unlabelled cell costs the unknown cost
	 * until it is seen, then the floor cost. */
	double cost(LabelSet labels, double roughness, Occupancy occupancy) const;
	/** The configured cost of a surface label (a registered class without
	 * a config key: its registry travelCost). */
	double surfaceCost(Label l) const;

	const TOptions& options() const { return m_options; }

private:
	/** u of one label; `obstacleCost` is what blocking labels cost. */
	double labelCost(Label l, double roughness, double obstacleCost) const;

	TOptions m_options;
};

}  // namespace semnav
