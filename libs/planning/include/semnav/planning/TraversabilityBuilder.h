/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <semnav/common/Label.h>
#include <semnav/common/LabelSet.h>
#include <semnav/planning/CellOccupancy.h>
#include <semnav/planning/TraversabilityGrid.h>

#include <array>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace semnav
{
/** Cost profiles of the paper (sec. 3, after eq. (12)). */
enum class CostProfile
{
	/** f_s(r1) = L if r1 < r, 0 otherwise; r = 5 cm. */
	Shortest,
	/** Eq. (13) as corrected in docs/design.md: f_s(r1) = L if r1 < r/2, 1 if
	 * r/2 <= r1 < r, 0 if r1 >= r; r = 30 cm. */
	Safe
};

/** Robot types: stairs are traversable only for walking robots. */
enum class RobotType
{
	Wheeled,
	Walking
};

/** "shortest" / "safe"; throws PlanningError on other names. */
CostProfile costProfileFromName(const std::string& name);
const char* costProfileName(CostProfile p);

/** Builds the traversability layer u from per-cell label sets and
 * occupancy (the paper's objects (s, u_s, r_s, f_s)).
 *
 * A cell is an obstacle when it is occupied, unobserved with u_unobserved =
 * blocked, or carries a label whose u_s is blocked (stairs always are for a
 * wheeled robot). Other cells get u = max over their labels of u_s (and
 * u_unobserved if unobserved). With a finite u_unobserved (exploring), an
 * unobserved cell that carries a blocking label (points seen above the
 * robot, or once from afar) is not entered but not inflated either. Around
 * obstacles, with d = distance from the cell centre to the obstacle cell's
 * square and r1 = d - robot_radius (the clearance of the robot's disc):
 * - C-space (eq. (2)): r1 < 0 (the disc would touch the obstacle) -> L;
 * - profile influence f_s(r1) with r = r_scale_<label> x the profile radius
 *   (occupancy obstacles: scale 1); u = max(u, f_s(r1)).
 * A cell's u is the max of all contributions (a set of labels is as costly
 * as its costliest member). */
class TraversabilityBuilder
{
public:
	/** Value of a blocked cost in TOptions (any value >= L blocks). */
	static constexpr double kBlocked = std::numeric_limits<double>::infinity();

	/** Options, INI section [Traversability] (config/planning.ini). Costs
	 * accept a number in [0, L] or the word `blocked` (kBlocked). */
	struct TOptions : public mrpt::config::CLoadableOptions
	{
		TOptions();

		void loadFromConfigFile(
		    const mrpt::config::CConfigFileBase& c,
		    const std::string& section) override;
		void saveToConfigFile(
		    mrpt::config::CConfigFileBase& c,
		    const std::string& section) const override;
		static const std::vector<std::string>& knownKeys();

		/** L: blocked value of u and goal value of g. */
		double L = 1e6;
		/** robot_type: wheeled | walking. */
		RobotType robotType = RobotType::Wheeled;
		/** robot_radius_m: C-space inflation. */
		double robotRadius = 0.25;
		/** profile: the default profile of build(). */
		CostProfile profile = CostProfile::Shortest;
		/** shortest_radius_m: r of the shortest profile. */
		double shortestRadius = 0.05;
		/** safe_radius_m: r of the safe profile (eq. (13)). */
		double safeRadius = 0.30;
		/** safe_ring_cost: f_s in [r/2, r) of eq. (13). */
		double safeRingCost = 1.0;
		/** u_unobserved: u of never-observed cells (default blocked). */
		double uUnobserved = kBlocked;
		/** inflate_unobserved: a blocked unobserved cell is an obstacle
		 * inflated like the others (true) or only not enterable (false: a
		 * robot may pass next to space it has not seen, e.g. the laser's
		 * blind zone around its own stops). */
		bool inflateUnobserved = false;
		/** goal_reach_m: goal regions extend this far beyond the closest
		 * allowed clearance (see goalRegionRadius()). */
		double goalReach = 0.30;
		/** u_<label>: traversability per label (by label id; defaults from
		 * the ClassRegistry: plannerCost, blocked for blocking classes).
		 * u_stairs (walking-only classes) is used by walking robots only. */
		std::array<double, kMaxLabelCount> labelU{};
		/** r_scale_<label>: multiplies the profile radius r for obstacles of
		 * this label (the paper's per-object r_s). */
		std::array<double, kMaxLabelCount> labelRadiusScale{};
	};

	TraversabilityBuilder();
	explicit TraversabilityBuilder(const TOptions& options);

	const TOptions& options() const { return m_options; }
	TOptions& options() { return m_options; }

	/** u of a cell holding only `l`, for the configured robot type (L =
	 * blocked). */
	double labelCost(Label l) const;

	/** Builds u. `labels` and `occupancy` are row-major over `geometry`;
	 * either may be empty (no labels / all free). Throws PlanningError on
	 * size mismatch or a bad geometry. */
	TraversabilityGrid build(
	    const GridGeometry& geometry, const std::vector<LabelSet>& labels,
	    const std::vector<CellOccupancy>& occupancy, CostProfile profile) const;
	/** As above with options().profile. */
	TraversabilityGrid build(
	    const GridGeometry& geometry, const std::vector<LabelSet>& labels,
	    const std::vector<CellOccupancy>& occupancy) const;

	/** As build(), with the per-cell u_s taken from `baseU` (e.g. the
	 * semantic map's travel-cost layer, which already knows grass roughness
	 * and robot type) instead of the u_<label> options: cells with baseU >=
	 * baseLethal are obstacles. Labels only give obstacles' r_scale. */
	TraversabilityGrid buildFromCost(
	    const GridGeometry& geometry, const std::vector<float>& baseU,
	    double baseLethal, const std::vector<LabelSet>& labels,
	    const std::vector<CellOccupancy>& occupancy, CostProfile profile) const;

	/** Reach of an input change (cells): a cell's u depends only on the
	 * inputs (labels, occupancy, base cost) of the cells within this many
	 * rows and columns of it (the largest inflation stencil, plus one for
	 * the test that makes an obstacle cell a source). */
	int reachCells(CostProfile profile, double resolution) const;

	/** Distance (m) from an object's cells within which goal cells are
	 * placed: robot_radius + the blocked clearance of the profile (scale 1) +
	 * goal_reach. */
	double goalRegionRadius(CostProfile profile) const;

private:
	/** One cell of an inflation stencil: offset and the u it imposes. */
	struct StencilTap
	{
		int dr, dc;
		double v;
	};

	TraversabilityGrid buildImpl(
	    const GridGeometry& geometry, const std::vector<float>* baseU,
	    double baseLethal, const std::vector<LabelSet>& labels,
	    const std::vector<CellOccupancy>& occupancy, CostProfile profile) const;
	/** Throws PlanningError unless the layer is empty or has `cells`. */
	static void checkLayerSize(
	    const char* layer, std::size_t size, std::size_t cells);
	/** Fills `u` with each cell's own cost (L for obstacles and cells not
	 * to enter) and returns each cell's obstacle influence scale (0: no
	 * obstacle, -1: no influence beyond the C-space). */
	std::vector<float> cellCosts(
	    const std::vector<float>* baseU, double baseLethal,
	    const std::vector<LabelSet>& labels,
	    const std::vector<CellOccupancy>& occupancy,
	    std::vector<double>& u) const;
	/** Obstacle cells with a free 8-neighbour, by influence scale. */
	static std::map<float, std::vector<std::size_t>> inflationSources(
	    const GridGeometry& g, const std::vector<float>& scale);
	/** The cells around an obstacle of scale `s` and their u (eq. (13)). */
	std::vector<StencilTap> influenceStencil(
	    float s, CostProfile profile, double resolution) const;
	/** Raises u around `cells` to the stencil's values. */
	static void inflate(
	    TraversabilityGrid& grid, const std::vector<StencilTap>& stencil,
	    const std::vector<std::size_t>& cells);

	TOptions m_options;
};

}  // namespace semnav
