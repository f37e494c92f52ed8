/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/Error.h>
#include <semnav/sim/SceneLoader.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

namespace semnav
{
namespace
{
constexpr double kDegToRad = M_PI / 180;
/** Instance ids go in the high byte of the ground-truth label images. */
constexpr std::size_t kMaxObjects = 255;

const std::vector<std::string> kSceneKeys = {
	"name",	  "bounds",	  "ceiling_height", "objects",
	"sensor", "odometry", "trajectory"};
const std::vector<std::string> kPrimitiveKeys = {
	"box", "cylinder", "stairs", "terrain"};

std::string joined(const std::vector<std::string>& v, const std::string& sep)
{
	std::string s;
	for (const auto& x : v) s += (s.empty() ? "" : sep) + x;
	return s;
}

std::string fmt(double v)
{
	std::ostringstream os;
	os << v;
	return os.str();
}

std::string child(const std::string& path, const std::string& key)
{
	return path.empty() ? key : path + "." + key;
}

std::string item(const std::string& path, std::size_t i)
{
	return path + "[" + std::to_string(i) + "]";
}

/** Short one-line description of a node for messages. */
std::string describe(const YAML::Node& n)
{
	if (!n.IsDefined()) return "nothing";
	switch (n.Type())
	{
		case YAML::NodeType::Null:
			return "null";
		case YAML::NodeType::Scalar:
		{
			std::string s = n.Scalar();
			std::replace(s.begin(), s.end(), '\n', ' ');
			if (s.size() > 40) s = s.substr(0, 37) + "...";
			return (n.Tag() == "!" ? "string '" : "'") + s + "'";
		}
		case YAML::NodeType::Sequence:
			return "a list";
		case YAML::NodeType::Map:
			return "a map";
		default:
			return "nothing";
	}
}

std::string labelNamesForObjects()
{
	std::vector<std::string> names;
	for (Label l : allLabels())
		if (l != Label::Unknown) names.push_back(labelName(l));
	return joined(names, ", ");
}

double polygonArea(const std::vector<mrpt::math::TPoint2D>& p)
{
	double a = 0;
	for (std::size_t i = 0; i < p.size(); i++)
	{
		const auto& q = p[i];
		const auto& r = p[(i + 1) % p.size()];
		a += q.x * r.y - r.x * q.y;
	}
	return 0.5 * std::abs(a);
}

/** Walks the YAML tree. Every error names the source, the 1-based line and
 * the key path (list indices 0-based), on one line. */
class Parser
{
   public:
	explicit Parser(const std::string& source) : m_source(source) {}

	[[noreturn]] void fail(
		int line, const std::string& path, const std::string& what) const
	{
		std::string msg = m_source;
		if (line > 0) msg += ":" + std::to_string(line);
		msg += ": ";
		if (!path.empty()) msg += path + ": ";
		throw SceneError(msg + what);
	}

	Scene scene(const YAML::Node& root) const;

   private:
	std::string m_source;

	static int lineOf(const YAML::Node& n, int fallback)
	{
		if (!n.IsDefined()) return fallback;
		const YAML::Mark m = n.Mark();
		return m.is_null() ? fallback : m.line + 1;
	}

	void expectMap(
		const YAML::Node& n, const std::string& path, int line) const
	{
		if (!n.IsDefined() || !n.IsMap())
			fail(lineOf(n, line), path, "expected a map, got " + describe(n));
	}

	void expectList(
		const YAML::Node& n, const std::string& path, int line) const
	{
		if (!n.IsDefined() || !n.IsSequence())
			fail(lineOf(n, line), path, "expected a list, got " + describe(n));
	}

	/** Rejects unknown and duplicate keys. */
	void checkKeys(
		const YAML::Node& map, const std::string& path,
		const std::vector<std::string>& allowed) const
	{
		std::set<std::string> seen;
		for (const auto& kv : map)
		{
			const int line = lineOf(kv.first, lineOf(map, 0));
			if (!kv.first.IsScalar())
				fail(line, path, "expected a key name, got " + describe(kv.first));
			const std::string key = kv.first.Scalar();
			if (std::find(allowed.begin(), allowed.end(), key) == allowed.end())
				fail(
					line, child(path, key),
					"unknown key (allowed: " + joined(allowed, ", ") + ")");
			if (!seen.insert(key).second)
				fail(line, child(path, key), "duplicate key");
		}
	}

	YAML::Node required(
		const YAML::Node& map, const std::string& path, int line,
		const std::string& key) const
	{
		const YAML::Node n = map[key];
		if (!n.IsDefined())
			fail(lineOf(map, line), child(path, key), "missing required key");
		return n;
	}

	std::string text(
		const YAML::Node& n, const std::string& path, int line) const
	{
		if (!n.IsDefined() || !n.IsScalar())
			fail(lineOf(n, line), path, "expected a name, got " + describe(n));
		return n.Scalar();
	}

	double number(
		const YAML::Node& n, const std::string& path, int line) const
	{
		const int l = lineOf(n, line);
		if (!n.IsDefined() || !n.IsScalar() || n.Tag() == "!")
			fail(l, path, "expected a number, got " + describe(n));
		double v = 0;
		if (!YAML::convert<double>::decode(n, v) || !std::isfinite(v))
			fail(l, path, "expected a number, got " + describe(n));
		return v;
	}

	double positive(
		const YAML::Node& n, const std::string& path, int line) const
	{
		const double v = number(n, path, line);
		if (!(v > 0)) fail(lineOf(n, line), path, "must be > 0, got " + fmt(v));
		return v;
	}

	double nonNegative(
		const YAML::Node& n, const std::string& path, int line) const
	{
		const double v = number(n, path, line);
		if (!(v >= 0))
			fail(lineOf(n, line), path, "must be >= 0, got " + fmt(v));
		return v;
	}

	int integer(
		const YAML::Node& n, const std::string& path, int line) const
	{
		const double v = number(n, path, line);
		if (v != std::floor(v) || std::abs(v) > 1e9)
			fail(lineOf(n, line), path, "expected an integer, got " + fmt(v));
		return static_cast<int>(v);
	}

	std::vector<double> numbers(
		const YAML::Node& n, const std::string& path, int line,
		std::size_t count) const
	{
		const int l = lineOf(n, line);
		const std::string expected = std::to_string(count) + " numbers";
		if (!n.IsDefined() || !n.IsSequence())
			fail(l, path, "expected a list of " + expected + ", got " + describe(n));
		if (n.size() != count)
			fail(
				l, path,
				"expected " + expected + ", got " + std::to_string(n.size()));
		std::vector<double> v;
		for (std::size_t i = 0; i < count; i++)
			v.push_back(number(n[i], item(path, i), l));
		return v;
	}

	mrpt::math::TPoint3D point3(
		const YAML::Node& n, const std::string& path, int line) const
	{
		const auto v = numbers(n, path, line, 3);
		return {v[0], v[1], v[2]};
	}

	mrpt::math::TPoint2D point2(
		const YAML::Node& n, const std::string& path, int line) const
	{
		const auto v = numbers(n, path, line, 2);
		return {v[0], v[1]};
	}

	/** Reads [min, max, step] in degrees, within [-limit, limit]. */
	void angleRange(
		const YAML::Node& n, const std::string& path, int line, double limitDeg,
		double& lo, double& hi, double& step) const
	{
		const auto v = numbers(n, path, line, 3);
		const int l = lineOf(n, line);
		if (!(v[0] < v[1]))
			fail(
				l, path,
				"min must be < max, got min " + fmt(v[0]) + ", max " + fmt(v[1]));
		if (!(v[2] > 0)) fail(l, path, "step must be > 0, got " + fmt(v[2]));
		if (v[0] < -limitDeg || v[1] > limitDeg)
			fail(
				l, path,
				"must lie within [" + fmt(-limitDeg) + ", " + fmt(limitDeg) +
					"] deg, got [" + fmt(v[0]) + ", " + fmt(v[1]) + "]");
		lo = v[0] * kDegToRad;
		hi = v[1] * kDegToRad;
		step = v[2] * kDegToRad;
	}

	Label label(const YAML::Node& n, const std::string& path, int line) const
	{
		const std::string name = text(n, path, line);
		const int l = lineOf(n, line);
		Label lab = Label::Unknown;
		try
		{
			lab = labelFromName(name);
		}
		catch (const UnknownLabelError&)
		{
			fail(
				l, path,
				"unknown label '" + name + "' (known: " +
					labelNamesForObjects() + ")");
		}
		if (lab == Label::Unknown)
			fail(l, path, "label 'unknown' is not allowed for an object");
		return lab;
	}

	BoxShape box(const YAML::Node& n, const std::string& path, int line) const
	{
		expectMap(n, path, line);
		checkKeys(n, path, {"center", "size", "yaw"});
		const int l = lineOf(n, line);
		BoxShape b;
		b.center =
			point3(required(n, path, l, "center"), child(path, "center"), l);
		const std::string sizePath = child(path, "size");
		const YAML::Node sizeNode = required(n, path, l, "size");
		const auto s = numbers(sizeNode, sizePath, l, 3);
		for (std::size_t i = 0; i < 3; i++)
			if (!(s[i] > 0))
				fail(
					lineOf(sizeNode[i], l), item(sizePath, i),
					"must be > 0, got " + fmt(s[i]));
		b.size = {s[0], s[1], s[2]};
		if (const YAML::Node y = n["yaw"]; y.IsDefined())
			b.yaw = number(y, child(path, "yaw"), l) * kDegToRad;
		return b;
	}

	CylinderShape cylinder(
		const YAML::Node& n, const std::string& path, int line) const
	{
		expectMap(n, path, line);
		checkKeys(n, path, {"center", "radius", "height"});
		const int l = lineOf(n, line);
		CylinderShape c;
		c.center =
			point3(required(n, path, l, "center"), child(path, "center"), l);
		c.radius =
			positive(required(n, path, l, "radius"), child(path, "radius"), l);
		c.height =
			positive(required(n, path, l, "height"), child(path, "height"), l);
		return c;
	}

	StairsShape stairs(
		const YAML::Node& n, const std::string& path, int line) const
	{
		expectMap(n, path, line);
		checkKeys(
			n, path, {"origin", "yaw", "steps", "rise", "run", "width"});
		const int l = lineOf(n, line);
		StairsShape s;
		s.origin =
			point2(required(n, path, l, "origin"), child(path, "origin"), l);
		if (const YAML::Node y = n["yaw"]; y.IsDefined())
			s.yaw = number(y, child(path, "yaw"), l) * kDegToRad;
		const YAML::Node stepsNode = required(n, path, l, "steps");
		s.steps = integer(stepsNode, child(path, "steps"), l);
		if (s.steps < 1)
			fail(
				lineOf(stepsNode, l), child(path, "steps"),
				"must be >= 1, got " + std::to_string(s.steps));
		s.rise = positive(required(n, path, l, "rise"), child(path, "rise"), l);
		s.run = positive(required(n, path, l, "run"), child(path, "run"), l);
		s.width =
			positive(required(n, path, l, "width"), child(path, "width"), l);
		return s;
	}

	TerrainShape terrain(
		const YAML::Node& n, const std::string& path, int line) const
	{
		expectMap(n, path, line);
		checkKeys(n, path, {"polygon", "roughness"});
		const int l = lineOf(n, line);
		TerrainShape t;
		const std::string polyPath = child(path, "polygon");
		const YAML::Node poly = required(n, path, l, "polygon");
		expectList(poly, polyPath, l);
		const int pl = lineOf(poly, l);
		if (poly.size() < 3)
			fail(
				pl, polyPath,
				"expected at least 3 vertices, got " +
					std::to_string(poly.size()));
		for (std::size_t i = 0; i < poly.size(); i++)
			t.polygon.push_back(point2(poly[i], item(polyPath, i), pl));
		if (!(polygonArea(t.polygon) > 1e-9))
			fail(pl, polyPath, "degenerate polygon (zero area)");
		t.roughness = nonNegative(
			required(n, path, l, "roughness"), child(path, "roughness"), l);
		return t;
	}

	/** The one primitive key of `owner` (already known to be present). */
	ScenePrimitive primitive(
		const YAML::Node& owner, const std::string& key,
		const std::string& ownerPath, int line) const
	{
		const YAML::Node n = owner[key];
		const std::string path = child(ownerPath, key);
		if (key == "box") return box(n, path, line);
		if (key == "cylinder") return cylinder(n, path, line);
		if (key == "stairs") return stairs(n, path, line);
		return terrain(n, path, line);
	}

	/** Keys of `map` among `candidates`; exactly one must be present. */
	std::string onlyOneOf(
		const YAML::Node& map, const std::string& path, int line,
		const std::vector<std::string>& candidates) const
	{
		std::vector<std::string> present;
		for (const auto& k : candidates)
			if (map[k].IsDefined()) present.push_back(k);
		const std::string list = joined(candidates, ", ");
		if (present.empty())
			fail(line, path, "missing shape: expected one of " + list);
		if (present.size() > 1)
			fail(
				line, path,
				"expected exactly one of " + list + ", got " +
					joined(present, " and "));
		return present.front();
	}

	SceneObject object(
		const YAML::Node& n, const std::string& path, int line) const
	{
		expectMap(n, path, line);
		std::vector<std::string> allowed = {"label"};
		allowed.insert(allowed.end(), kPrimitiveKeys.begin(), kPrimitiveKeys.end());
		allowed.push_back("parts");
		checkKeys(n, path, allowed);
		const int l = lineOf(n, line);
		SceneObject o;
		o.line = l;
		o.label = label(required(n, path, l, "label"), child(path, "label"), l);
		std::vector<std::string> shapes = kPrimitiveKeys;
		shapes.push_back("parts");
		const std::string key = onlyOneOf(n, path, l, shapes);
		if (key != "parts")
		{
			o.parts.push_back(primitive(n, key, path, l));
			return o;
		}
		const std::string partsPath = child(path, "parts");
		const YAML::Node parts = n["parts"];
		expectList(parts, partsPath, l);
		if (parts.size() == 0)
			fail(lineOf(parts, l), partsPath, "expected at least 1 part, got 0");
		for (std::size_t i = 0; i < parts.size(); i++)
		{
			const std::string pp = item(partsPath, i);
			const YAML::Node p = parts[i];
			expectMap(p, pp, lineOf(parts, l));
			checkKeys(p, pp, kPrimitiveKeys);
			const int ppl = lineOf(p, l);
			const std::string k = onlyOneOf(p, pp, ppl, kPrimitiveKeys);
			o.parts.push_back(primitive(p, k, pp, ppl));
		}
		return o;
	}

	void sensor(
		const YAML::Node& n, const std::string& path, int line,
		SensorSpec& s) const
	{
		expectMap(n, path, line);
		checkKeys(n, path, {"mount", "phi", "theta", "max_range", "range_noise"});
		const int l = lineOf(n, line);
		if (const YAML::Node m = n["mount"]; m.IsDefined())
			s.mount = point3(m, child(path, "mount"), l);
		if (const YAML::Node p = n["phi"]; p.IsDefined())
			angleRange(
				p, child(path, "phi"), l, 180, s.phiMin, s.phiMax, s.phiStep);
		if (const YAML::Node t = n["theta"]; t.IsDefined())
			angleRange(
				t, child(path, "theta"), l, 90, s.thetaMin, s.thetaMax,
				s.thetaStep);
		if (const YAML::Node r = n["max_range"]; r.IsDefined())
			s.maxRange = positive(r, child(path, "max_range"), l);
		if (const YAML::Node r = n["range_noise"]; r.IsDefined())
			s.rangeNoise = nonNegative(r, child(path, "range_noise"), l);
	}

	void odometry(
		const YAML::Node& n, const std::string& path, int line,
		OdometrySpec& o) const
	{
		expectMap(n, path, line);
		checkKeys(
			n, path,
			{"trans_noise", "rot_noise_deg_per_m", "rot_bias_deg_per_m"});
		const int l = lineOf(n, line);
		if (const YAML::Node v = n["trans_noise"]; v.IsDefined())
			o.transNoise = nonNegative(v, child(path, "trans_noise"), l);
		if (const YAML::Node v = n["rot_noise_deg_per_m"]; v.IsDefined())
			o.rotNoisePerM =
				nonNegative(v, child(path, "rot_noise_deg_per_m"), l) *
				kDegToRad;
		if (const YAML::Node v = n["rot_bias_deg_per_m"]; v.IsDefined())
			o.rotBiasPerM =
				number(v, child(path, "rot_bias_deg_per_m"), l) * kDegToRad;
	}
};

Scene Parser::scene(const YAML::Node& root) const
{
	if (!root.IsDefined() || !root.IsMap())
		fail(
			lineOf(root, 1), "",
			"expected a scene map (keys: " + joined(kSceneKeys, ", ") +
				"), got " + describe(root));
	checkKeys(root, "", kSceneKeys);
	const int rl = lineOf(root, 1);
	Scene sc;

	const YAML::Node nameNode = required(root, "", rl, "name");
	sc.name = text(nameNode, "name", rl);
	const bool nameOk = !sc.name.empty() && sc.name[0] != '.' &&
		std::all_of(sc.name.begin(), sc.name.end(), [](unsigned char c) {
							return std::isalnum(c) || c == '_' || c == '-' || c == '.';
						});
	if (!nameOk)
		fail(
			lineOf(nameNode, rl), "name",
			"'" + sc.name +
				"' is not a valid file name (use letters, digits, _ - .)");

	const YAML::Node boundsNode = required(root, "", rl, "bounds");
	const auto b = numbers(boundsNode, "bounds", rl, 4);
	sc.bounds = {b[0], b[1], b[2], b[3]};
	if (!(b[2] > b[0]) || !(b[3] > b[1]))
		fail(
			lineOf(boundsNode, rl), "bounds",
			"expected xmin < xmax and ymin < ymax, got [" + fmt(b[0]) + ", " +
				fmt(b[1]) + ", " + fmt(b[2]) + ", " + fmt(b[3]) + "]");

	if (const YAML::Node c = root["ceiling_height"]; c.IsDefined())
		sc.ceilingHeight = positive(c, "ceiling_height", rl);

	if (const YAML::Node objs = root["objects"]; objs.IsDefined())
	{
		expectList(objs, "objects", rl);
		const int ol = lineOf(objs, rl);
		if (objs.size() > kMaxObjects)
			fail(
				lineOf(objs[kMaxObjects], ol), item("objects", kMaxObjects),
				"too many objects: " + std::to_string(objs.size()) +
					", at most " + std::to_string(kMaxObjects) +
					" (instance ids are stored in a byte)");
		for (std::size_t i = 0; i < objs.size(); i++)
		{
			SceneObject o = object(objs[i], item("objects", i), ol);
			o.id = static_cast<int>(i) + 1;
			sc.objects.push_back(std::move(o));
		}
	}

	if (const YAML::Node s = root["sensor"]; s.IsDefined())
		sensor(s, "sensor", rl, sc.sensor);
	if (const YAML::Node o = root["odometry"]; o.IsDefined())
		odometry(o, "odometry", rl, sc.odometry);

	const YAML::Node traj = required(root, "", rl, "trajectory");
	expectList(traj, "trajectory", rl);
	const int tl = lineOf(traj, rl);
	if (traj.size() == 0)
		fail(tl, "trajectory", "expected at least 1 pose, got 0");
	for (std::size_t i = 0; i < traj.size(); i++)
	{
		const std::string path = item("trajectory", i);
		const auto p = numbers(traj[i], path, tl, 3);
		if (!sc.bounds.contains(p[0], p[1]))
			fail(
				lineOf(traj[i], tl), path,
				"pose (" + fmt(p[0]) + ", " + fmt(p[1]) +
					") is outside the bounds");
		sc.trajectory.emplace_back(p[0], p[1], p[2] * kDegToRad);
	}
	return sc;
}

}  // namespace

Scene SceneLoader::loadFile(const std::string& path)
{
	std::error_code ec;
	if (!std::filesystem::is_regular_file(path, ec))
		throw SceneError("cannot open scene file " + path);
	std::ifstream f(path, std::ios::binary);
	if (!f) throw SceneError("cannot open scene file " + path);
	std::ostringstream text;
	text << f.rdbuf();
	if (f.bad()) throw SceneError("cannot read scene file " + path);
	return parse(text.str(), path);
}

Scene SceneLoader::parse(
	const std::string& yamlText, const std::string& sourceName)
{
	const Parser parser(sourceName);
	std::vector<YAML::Node> docs;
	try
	{
		docs = YAML::LoadAll(yamlText);
	}
	catch (const YAML::Exception& e)
	{
		parser.fail(
			e.mark.is_null() ? 0 : e.mark.line + 1, "",
			"YAML syntax error: " + e.msg);
	}
	if (docs.empty()) parser.fail(1, "", "empty scene file");
	if (docs.size() > 1)
		parser.fail(
			docs[1].Mark().is_null() ? 0 : docs[1].Mark().line + 1, "",
			"expected one YAML document, got " + std::to_string(docs.size()));
	try
	{
		return parser.scene(docs.front());
	}
	catch (const YAML::Exception& e)
	{
		// Not expected: the parser checks types before converting.
		parser.fail(
			e.mark.is_null() ? 0 : e.mark.line + 1, "",
			"YAML error: " + e.msg);
	}
}

}  // namespace semnav
