/* semnav: semantic navigation from tilting-laser sweeps */
#include "SceneDraft.h"

#include <cmath>
#include <cstdlib>
#include <sstream>

namespace semnav::detail
{
using mrpt::math::TPoint2D;

namespace
{
constexpr double kDeg = M_PI / 180;

std::string vec(std::initializer_list<double> v)
{
	std::string s = "[";
	for (const double x : v) s += (s.size() > 1 ? ", " : "") + formatNumber(x);
	return s + "]";
}

std::string partText(const DraftPart& p)
{
	switch (p.kind)
	{
		case DraftPart::Kind::Box:
			return "box: {center: " + vec({p.x, p.y, p.z}) +
			       ", size: " + vec({p.sx, p.sy, p.sz}) +
			       ", yaw: " + formatNumber(p.yawDeg) + "}";
		case DraftPart::Kind::Cylinder:
			return "cylinder: {center: " + vec({p.x, p.y, p.z}) +
			       ", radius: " + formatNumber(p.radius) +
			       ", height: " + formatNumber(p.height) + "}";
		case DraftPart::Kind::Stairs:
			return "stairs: {origin: " + vec({p.x, p.y}) +
			       ", yaw: " + formatNumber(p.yawDeg) +
			       ", steps: " + std::to_string(p.steps) +
			       ", rise: " + formatNumber(p.rise) +
			       ", run: " + formatNumber(p.run) +
			       ", width: " + formatNumber(p.width) + "}";
	}
	return {};
}
}  // namespace

std::string formatNumber(double v)
{
	const long long mm = std::llround(v * 1000.0);
	if (mm == 0) return "0";
	const long long a = std::llabs(mm);
	std::string s = (mm < 0 ? "-" : "") + std::to_string(a / 1000);
	long long frac = a % 1000;
	if (frac == 0) return s;
	std::string f = std::to_string(1000 + frac).substr(1);
	while (f.back() == '0') f.pop_back();
	return s + "." + f;
}

DraftPart DraftPart::box(
    double x, double y, double z, double sx, double sy, double sz,
    double yawDeg)
{
	DraftPart p;
	p.kind = Kind::Box;
	p.x = x, p.y = y, p.z = z, p.sx = sx, p.sy = sy, p.sz = sz;
	p.yawDeg = yawDeg;
	return p;
}

DraftPart DraftPart::cylinder(
    double x, double y, double z, double radius, double height)
{
	DraftPart p;
	p.kind = Kind::Cylinder;
	p.x = x, p.y = y, p.z = z, p.radius = radius, p.height = height;
	return p;
}

DraftPart DraftPart::stairs(
    double x, double y, double yawDeg, int steps, double rise, double run,
    double width)
{
	DraftPart p;
	p.kind = Kind::Stairs;
	p.x = x, p.y = y, p.yawDeg = yawDeg, p.steps = steps;
	p.rise = rise, p.run = run, p.width = width;
	return p;
}

Polygon2D DraftPart::footprint(double maxBottom) const
{
	switch (kind)
	{
		case Kind::Box:
			if (z - sz / 2 > maxBottom) return {};
			return rectPolygon(x, y, sx, sy, yawDeg * kDeg);
		case Kind::Cylinder:
			if (z - height / 2 > maxBottom) return {};
			return circlePolygon(x, y, radius);
		case Kind::Stairs:
		{
			const double L = steps * run, a = yawDeg * kDeg;
			return rectPolygon(
			    x + std::cos(a) * L / 2, y + std::sin(a) * L / 2, L, width, a);
		}
	}
	return {};
}

double GeneratorRandom::uniform(double lo, double hi)
{
	const double u = static_cast<double>(m_engine() >> 11) * 0x1p-53;
	return lo + (hi - lo) * u;
}

int GeneratorRandom::uniformInt(int lo, int hi)
{
	const auto span = static_cast<uint64_t>(hi - lo + 1);
	return lo + static_cast<int>(m_engine() % span);
}

SceneDraft::SceneDraft(std::string name, uint64_t seed)
    : m_name(std::move(name)), m_rng(seed)
{
}

void SceneDraft::setBounds(double xmin, double ymin, double xmax, double ymax)
{
	m_bounds[0] = xmin, m_bounds[1] = ymin;
	m_bounds[2] = xmax, m_bounds[3] = ymax;
}

void SceneDraft::add(
    Label label, const std::vector<DraftPart>& parts, bool structural)
{
	const std::string l = labelName(label);
	if (parts.size() == 1)
		m_objects.push_back(
		    "  - {label: " + l + ", " + partText(parts[0]) + "}");
	else
	{
		std::string s = "  - label: " + l + "\n    parts:";
		for (const auto& p : parts) s += "\n      - {" + partText(p) + "}";
		m_objects.push_back(s);
	}
	for (const auto& p : parts)
		if (auto fp = p.footprint(kObstacleTop); !fp.empty())
		{
			m_footprints.push_back(std::move(fp));
			m_structural.push_back(structural);
		}
}

void SceneDraft::addTerrain(
    Label label, const Polygon2D& polygon, double roughness)
{
	std::string s =
	    "  - {label: " + labelName(label) + ", terrain: {polygon: [";
	for (std::size_t i = 0; i < polygon.size(); i++)
		s += (i ? ", " : "") + vec({polygon[i].x, polygon[i].y});
	s += "], roughness: " + formatNumber(roughness) + "}}";
	m_objects.push_back(s);
}

void SceneDraft::addKeepOut(const TPoint2D& a, const TPoint2D& b, double radius)
{
	m_keepOuts.push_back({a, b, radius});
}

bool SceneDraft::isFree(const Polygon2D& fp, double margin) const
{
	// Furniture stands against walls: a structural footprint only must not
	// be entered (FurniturePlacer keeps 2 mm off it).
	for (std::size_t i = 0; i < m_footprints.size(); i++)
		if (distPolygons(fp, m_footprints[i]) <
		    (m_structural[i] ? 0.001 : margin))
			return false;
	for (const auto& k : m_keepOuts)
		if (distSegmentPolygon(k.a, k.b, fp) < k.radius) return false;
	return true;
}

bool SceneDraft::isFree(
    const std::vector<DraftPart>& parts, double margin) const
{
	for (const auto& p : parts)
		if (const auto fp = p.footprint(kObstacleTop);
		    !fp.empty() && !isFree(fp, margin))
			return false;
	return true;
}

double SceneDraft::clearance(const TPoint2D& a, const TPoint2D& b) const
{
	double d = 1e9;
	for (const auto& o : m_footprints)
		d = std::min(d, distSegmentPolygon(a, b, o));
	return d;
}

void SceneDraft::addPose(double x, double y, double yawDeg)
{
	double yaw = std::fmod(yawDeg, 360.0);
	if (yaw > 180) yaw -= 360;
	if (yaw <= -180) yaw += 360;
	m_poses.push_back({x, y, yaw});
}

std::string SceneDraft::trajectoryProblem(
    double poseClearance, double pathClearance) const
{
	if (m_poses.empty()) return "no trajectory";
	for (std::size_t i = 0; i < m_poses.size(); i++)
	{
		const TPoint2D p(m_poses[i].x, m_poses[i].y);
		if (p.x < m_bounds[0] || p.x > m_bounds[2] || p.y < m_bounds[1] ||
		    p.y > m_bounds[3])
			return "pose " + std::to_string(i) + " outside the bounds";
		if (clearance(p, p) < poseClearance)
			return "pose " + std::to_string(i) + " too close to an object";
		if (i > 0 &&
		    clearance(TPoint2D(m_poses[i - 1].x, m_poses[i - 1].y), p) <
		        pathClearance)
			return "path to pose " + std::to_string(i) + " blocked";
	}
	return {};
}

std::string SceneDraft::yaml() const
{
	std::ostringstream o;
	for (const auto& c : m_comments) o << "# " << c << "\n";
	o << "name: " << m_name << "\n";
	o << "bounds: " << vec({m_bounds[0], m_bounds[1], m_bounds[2], m_bounds[3]})
	  << "\n";
	if (m_ceiling > 0)
		o << "ceiling_height: " << formatNumber(m_ceiling) << "\n";
	o << "objects:\n";
	for (const auto& s : m_objects) o << s << "\n";
	o << "odometry: {trans_noise: 0.02, rot_noise_deg_per_m: 2, "
	     "rot_bias_deg_per_m: "
	  << formatNumber(m_rotBias) << "}\n";
	o << "trajectory:\n";
	for (const auto& p : m_poses)
		o << "  - " << vec({p.x, p.y, p.yawDeg}) << "\n";
	return o.str();
}

}  // namespace semnav::detail
