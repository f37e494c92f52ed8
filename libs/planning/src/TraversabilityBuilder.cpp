/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/config/CConfigFileBase.h>
#include <semnav/common/ClassRegistry.h>
#include <semnav/common/Error.h>
#include <semnav/common/OptionTable.h>
#include <semnav/planning/PlanningErrors.h>
#include <semnav/planning/TraversabilityBuilder.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <map>

namespace semnav
{
CostProfile costProfileFromName(const std::string& name)
{
	if (name == "shortest") return CostProfile::Shortest;
	if (name == "safe") return CostProfile::Safe;
	throw PlanningError(
	    "unknown cost profile '" + name + "' (known: shortest, safe)");
}

const char* costProfileName(CostProfile p)
{
	return p == CostProfile::Safe ? "safe" : "shortest";
}

namespace
{
std::string lowerTrimmed(std::string s)
{
	const auto b = s.find_first_not_of(" \t\r\n");
	const auto e = s.find_last_not_of(" \t\r\n");
	s = b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
	std::transform(
	    s.begin(), s.end(), s.begin(),
	    [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
	return s;
}

using O = TraversabilityBuilder::TOptions;
constexpr double kBlocked = TraversabilityBuilder::kBlocked;

/** A cost u in [0, L] or the word "blocked"; values >= L block, and so do
 * kept values that reach a new L. */
void addCost(
    OptionTable<O>& t, const std::string& key,
    const std::function<double&(O&)>& at, const std::string& doc)
{
	t.custom(
	    key,
	    [=](O& o, const mrpt::config::CConfigFileBase& c, const std::string& s)
	    {
		    double& u = at(o);
		    if (u >= o.L) u = kBlocked;
		    const std::string text =
		        lowerTrimmed(c.read_string(s, key, "", false));
		    if (text == "blocked")
			    u = kBlocked;
		    else if (!text.empty())
		    {
			    u = readChecked(c, s, key, u, 0, o.L);
			    if (u >= o.L) u = kBlocked;
		    }
	    },
	    [=](const O& o)
	    {
		    const double u = at(const_cast<O&>(o));
		    return u >= o.L ? std::string("blocked") : numberText(u);
	    },
	    doc);
}

OptionTable<O> makeOptionTable()
{
	OptionTable<O> t;
	t.real(
	     "L", &O::L, 1, 1e9,
	     "The paper's L: u = L blocks a cell; must exceed any path cost.")
	    .choice(
	        "robot_type", &O::robotType,
	        {{RobotType::Wheeled, "wheeled"}, {RobotType::Walking, "walking"}},
	        "wheeled | walking: stairs are traversable for walking robots "
	        "only.")
	    .real(
	        "robot_radius_m", &O::robotRadius, 0, 5,
	        "Cells where the robot's disc would touch an obstacle are "
	        "blocked.")
	    .choice(
	        "profile", &O::profile,
	        {{CostProfile::Shortest, "shortest"}, {CostProfile::Safe, "safe"}},
	        "Default cost profile: shortest | safe.")
	    .real(
	        "shortest_radius_m", &O::shortestRadius, 0, 5,
	        "Shortest profile: blocked below this clearance.")
	    .real(
	        "safe_radius_m", &O::safeRadius, 0, 5,
	        "Safe profile: blocked below r/2 of clearance, safe_ring_cost "
	        "up to r.");
	addCost(
	    t, "safe_ring_cost", [](O& o) -> double& { return o.safeRingCost; },
	    "u of the safe profile's ring [r/2, r): [0, L] or blocked.");
	addCost(
	    t, "u_unobserved", [](O& o) -> double& { return o.uUnobserved; },
	    "u of never-observed cells: [0, L] or blocked.");
	t.flag(
	     "inflate_unobserved", &O::inflateUnobserved,
	     "A blocked unobserved cell is inflated like an obstacle.")
	    .real(
	        "goal_reach_m", &O::goalReach, 0, 10,
	        "Goal regions extend this far beyond the closest allowed "
	        "position.");
	for (Label l : allLabels())
		addCost(
		    t, "u_" + labelName(l),
		    [i = static_cast<std::size_t>(l)](O& o) -> double&
		    { return o.labelU[i]; },
		    "u of " + labelName(l) +
		        " cells: [0, L] or blocked (an "
		        "obstacle).");
	for (Label l : allLabels())
	{
		const auto i = static_cast<std::size_t>(l);
		t.custom(
		    "r_scale_" + labelName(l),
		    [i, key = "r_scale_" + labelName(l)](
		        O& o, const mrpt::config::CConfigFileBase& c,
		        const std::string& s)
		    {
			    o.labelRadiusScale[i] =
			        readChecked(c, s, key, o.labelRadiusScale[i], 0, 10);
		    },
		    [i](const O& o) { return numberText(o.labelRadiusScale[i]); },
		    "Influence radius scale around " + labelName(l) +
		        " (0: C-space only).");
	}
	return t;
}

const OptionTable<O>& optionTable()
{
	static const OptionTable<O> t = makeOptionTable();
	return t;
}
}  // namespace

const std::vector<std::string>& TraversabilityBuilder::TOptions::knownKeys()
{
	static const std::vector<std::string> keys = optionTable().keys();
	return keys;
}

SEMNAV_OPTIONS_FROM_TABLE(TraversabilityBuilder::TOptions, optionTable())

TraversabilityBuilder::TOptions::TOptions()
{
	labelU.fill(0);
	for (Label l : allLabels())
	{
		const ClassInfo& c = classInfo(l);
		labelU[static_cast<std::size_t>(l)] =
		    c.passage == ClassInfo::Passage::Blocking ? kBlocked
		                                              : c.plannerCost;
	}
	labelRadiusScale.fill(1);
}

TraversabilityBuilder::TraversabilityBuilder()
    : TraversabilityBuilder(TOptions())
{
}

TraversabilityBuilder::TraversabilityBuilder(const TOptions& options)
    : m_options(options)
{
}

double TraversabilityBuilder::labelCost(Label l) const
{
	if (classInfo(l).walkingOnly && m_options.robotType == RobotType::Wheeled)
		return m_options.L;
	return std::min(m_options.labelU[static_cast<std::size_t>(l)], m_options.L);
}

double TraversabilityBuilder::goalRegionRadius(CostProfile profile) const
{
	const double clearance = profile == CostProfile::Safe
	                             ? 0.5 * m_options.safeRadius
	                             : m_options.shortestRadius;
	return m_options.robotRadius + clearance + m_options.goalReach;
}

TraversabilityGrid TraversabilityBuilder::build(
    const GridGeometry& geometry, const std::vector<LabelSet>& labels,
    const std::vector<CellOccupancy>& occupancy) const
{
	return build(geometry, labels, occupancy, m_options.profile);
}

TraversabilityGrid TraversabilityBuilder::build(
    const GridGeometry& g, const std::vector<LabelSet>& labels,
    const std::vector<CellOccupancy>& occupancy, CostProfile profile) const
{
	return buildImpl(g, nullptr, 0, labels, occupancy, profile);
}

TraversabilityGrid TraversabilityBuilder::buildFromCost(
    const GridGeometry& g, const std::vector<float>& baseU, double baseLethal,
    const std::vector<LabelSet>& labels,
    const std::vector<CellOccupancy>& occupancy, CostProfile profile) const
{
	if (baseU.size() != g.cellCount())
		throw PlanningError(
		    "cost layer has " + std::to_string(baseU.size()) +
		    " cells, the grid " + std::to_string(g.cellCount()));
	return buildImpl(g, &baseU, baseLethal, labels, occupancy, profile);
}

TraversabilityGrid TraversabilityBuilder::buildImpl(
    const GridGeometry& g, const std::vector<float>* baseU, double baseLethal,
    const std::vector<LabelSet>& labels,
    const std::vector<CellOccupancy>& occupancy, CostProfile profile) const
{
	validatePlanningGrid(g);
	checkLayerSize("label", labels.size(), g.cellCount());
	checkLayerSize("occupancy", occupancy.size(), g.cellCount());
	TraversabilityGrid grid(g, m_options.L, 0);
	const std::vector<float> scale =
	    cellCosts(baseU, baseLethal, labels, occupancy, grid.values());
	for (const auto& [s, cells] : inflationSources(g, scale))
		inflate(grid, influenceStencil(s, profile, g.resolution), cells);
	return grid;
}

void TraversabilityBuilder::checkLayerSize(
    const char* layer, std::size_t size, std::size_t cells)
{
	if (size != 0 && size != cells)
		throw PlanningError(
		    std::string(layer) + " layer has " + std::to_string(size) +
		    " cells, the grid " + std::to_string(cells));
}

std::vector<float> TraversabilityBuilder::cellCosts(
    const std::vector<float>* baseU, double baseLethal,
    const std::vector<LabelSet>& labels,
    const std::vector<CellOccupancy>& occupancy, std::vector<double>& u) const
{
	const double L = m_options.L;
	const std::size_t n = u.size();
	std::array<double, kMaxLabelCount> cost{};
	for (Label l : allLabels())
		cost[static_cast<std::size_t>(l)] = labelCost(l);
	const std::size_t labelCount = allLabels().size();
	// Obstacles get the influence scale of their costliest reason (0 = not
	// an obstacle, -1 = obstacle with no influence beyond the C-space).
	std::vector<float> scale(n, 0.f);
	const auto markObstacle = [&](std::size_t i, double s)
	{
		const float v = s > 0 ? static_cast<float>(s) : -1.f;
		scale[i] = std::max(scale[i], v);
		if (scale[i] == 0.f) scale[i] = v;
	};
	// Unobserved cells that are blocked but not inflated.
	std::vector<uint8_t> notEnterable(n, 0);
	const bool inflateUnknown = m_options.inflateUnobserved;
	// Unseen cells may be crossed (at u_unobserved): the robot explores.
	const bool exploring = m_options.uUnobserved < L;
	for (std::size_t i = 0; i < n; i++)
	{
		double ui = 0;
		const bool unknown =
		    !occupancy.empty() && occupancy[i] == CellOccupancy::Unknown;
		if (!occupancy.empty())
		{
			if (occupancy[i] == CellOccupancy::Occupied)
				markObstacle(i, 1);
			else if (unknown)
			{
				if (exploring)
					ui = std::max(ui, m_options.uUnobserved);
				else if (inflateUnknown)
					markObstacle(i, 1);
				else
					notEnterable[i] = 1;
			}
		}
		const LabelSet::mask_t mask = labels.empty() ? 0u : labels[i].mask();
		if (baseU)
		{
			if ((*baseU)[i] >= baseLethal)
			{
				// Influence of the costliest obstacle label seen there.
				double s = 0;
				bool labelled = false;
				for (std::size_t k = 0; k < labelCount; k++)
					if ((mask & (1u << k)) && cost[k] >= L)
					{
						labelled = true;
						s = std::max(s, m_options.labelRadiusScale[k]);
					}
				if (!labelled && unknown)
				{
					// Lethal only for being unseen: u_unobserved decides.
					if (exploring)
						ui = std::max(ui, m_options.uUnobserved);
					else if (inflateUnknown)
						markObstacle(i, 1);
					else
						notEnterable[i] = 1;
				}
				else if (unknown && exploring)
				{
					// An obstacle label without occupancy evidence (points
					// above the robot, or seen once from afar): exploring,
					// the cell is not entered but does not push the plan
					// away (a stray label must not wall off unseen space).
					notEnterable[i] = 1;
				}
				else
					markObstacle(i, labelled ? s : 1);
			}
			else
				ui = std::max(ui, static_cast<double>((*baseU)[i]));
		}
		else
			for (std::size_t k = 0; k < labelCount; k++)
			{
				if (!(mask & (1u << k))) continue;
				if (cost[k] < L)
					ui = std::max(ui, cost[k]);
				else if (unknown && exploring)
					notEnterable[i] = 1;
				else
					markObstacle(i, m_options.labelRadiusScale[k]);
			}
		u[i] = scale[i] != 0.f || notEnterable[i] ? L : ui;
	}
	return scale;
}

std::map<float, std::vector<std::size_t>>
TraversabilityBuilder::inflationSources(
    const GridGeometry& g, const std::vector<float>& scale)
{
	// Only obstacle cells with a free 8-neighbour can be the nearest
	// obstacle of a free cell.
	std::map<float, std::vector<std::size_t>> sources;
	for (int r = 0; r < g.rows; r++)
		for (int c = 0; c < g.cols; c++)
		{
			const std::size_t i = g.index(r, c);
			if (scale[i] == 0.f) continue;
			bool boundary = false;
			for (int dr = -1; dr <= 1 && !boundary; dr++)
				for (int dc = -1; dc <= 1; dc++)
					if (g.contains(r + dr, c + dc) &&
					    scale[g.index(r + dr, c + dc)] == 0.f)
					{
						boundary = true;
						break;
					}
			if (boundary) sources[std::max(scale[i], 0.f)].push_back(i);
		}
	return sources;
}

int TraversabilityBuilder::reachCells(CostProfile profile, double res) const
{
	float scale = 1;
	for (const double s : m_options.labelRadiusScale)
		scale = std::max(scale, static_cast<float>(s));
	int reach = 0;
	for (const auto& t : influenceStencil(scale, profile, res))
		reach = std::max({reach, std::abs(t.dr), std::abs(t.dc)});
	return reach + 1;
}

std::vector<TraversabilityBuilder::StencilTap>
TraversabilityBuilder::influenceStencil(
    float s, CostProfile profile, double res) const
{
	const double L = m_options.L, R = m_options.robotRadius;
	// f_s(r1) with r1 = d - R: [0, rBlock) -> L, [rBlock, rRing) -> ring.
	double rBlock = 0, rRing = 0, ring = 0;
	if (profile == CostProfile::Shortest)
		rBlock = rRing = s * m_options.shortestRadius;
	else
	{
		rBlock = 0.5 * s * m_options.safeRadius;
		rRing = s * m_options.safeRadius;
		ring = m_options.safeRingCost;
	}
	std::vector<StencilTap> stencil;
	const int k = static_cast<int>(std::ceil((R + rRing) / res)) + 1;
	for (int dr = -k; dr <= k; dr++)
		for (int dc = -k; dc <= k; dc++)
		{
			const double ex = std::max(0.0, std::abs(dc) - 0.5) * res;
			const double ey = std::max(0.0, std::abs(dr) - 0.5) * res;
			const double r1 = std::hypot(ex, ey) - R;
			const double v =
			    r1 < rBlock ? L : (r1 < rRing ? std::min(ring, L) : 0.0);
			if (v > 0) stencil.push_back({dr, dc, v});
		}
	return stencil;
}

void TraversabilityBuilder::inflate(
    TraversabilityGrid& grid, const std::vector<StencilTap>& stencil,
    const std::vector<std::size_t>& cells)
{
	const GridGeometry& g = grid.geometry();
	auto& u = grid.values();
	for (std::size_t i : cells)
	{
		const int r = static_cast<int>(i / g.cols);
		const int c = static_cast<int>(i % g.cols);
		for (const auto& t : stencil)
		{
			const int rr = r + t.dr, cc = c + t.dc;
			if (!g.contains(rr, cc)) continue;
			double& ui = u[g.index(rr, cc)];
			if (t.v > ui) ui = t.v;
		}
	}
}

}  // namespace semnav
