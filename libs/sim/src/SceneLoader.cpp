/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/Error.h>
#include <semnav/sim/SceneLoader.h>
#include <yaml-cpp/eventhandler.h>
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
/** Largest length (sizes, heights, ranges; m): a building, not a planet. */
constexpr double kMaxLength = 1000;
/** Largest coordinate magnitude (m): scenes are local frames. */
constexpr double kMaxCoordinate = 10000;
/** Most steps of one stairs object (each step is a ray-cast solid). */
constexpr int kMaxSteps = 1000;
/** Finest beam and tilt step (deg): finer than an LMS2xx's 0.25 deg; a
 * sweep has at most 3601 x 1801 pixels. */
constexpr double kMinAngleStepDeg = 0.1;

const std::vector<std::string> kSceneKeys = {
    "name",   "bounds",   "ceiling_height", "objects",
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

/** A value in the tree: the node (undefined if absent), its key path and
 * the line to report when the node has none of its own (null values). */
struct Field
{
	YAML::Node node;
	std::string path;
	int line = 0;

	bool present() const { return node.IsDefined(); }
};

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

	[[noreturn]] void fail(const Field& f, const std::string& what) const
	{
		fail(lineOf(f), f.path, what);
	}

	static int lineOf(const YAML::Node& n, int fallback)
	{
		// A null value's mark points past it (often the next line).
		if (!n.IsDefined() || n.IsNull()) return fallback;
		const YAML::Mark m = n.Mark();
		return m.is_null() ? fallback : m.line + 1;
	}

	static int lineOf(const Field& f) { return lineOf(f.node, f.line); }

	Scene scene(const YAML::Node& root) const;

private:
	std::string m_source;

	/** Child `key` of the map `f`; its line is the key's line. */
	static Field field(const Field& f, const std::string& key)
	{
		Field c{f.node[key], child(f.path, key), lineOf(f)};
		for (const auto& kv : f.node)
			if (kv.first.IsScalar() && kv.first.Scalar() == key)
				c.line = lineOf(kv.first, c.line);
		return c;
	}

	/** Element i of the list `f`. */
	static Field element(const Field& f, std::size_t i)
	{
		return {f.node[i], item(f.path, i), lineOf(f)};
	}

	Field required(const Field& f, const std::string& key) const
	{
		Field c = field(f, key);
		if (!c.present()) fail(c, "missing required key");
		return c;
	}

	void expectMap(const Field& f) const
	{
		if (!f.present() || !f.node.IsMap())
			fail(f, "expected a map, got " + describe(f.node));
	}

	void expectList(const Field& f) const
	{
		if (!f.present() || !f.node.IsSequence())
			fail(f, "expected a list, got " + describe(f.node));
	}

	/** Rejects unknown and duplicate keys of the map `f`. */
	void checkKeys(
	    const Field& f, const std::vector<std::string>& allowed) const
	{
		std::set<std::string> seen;
		for (const auto& kv : f.node)
		{
			const int line = lineOf(kv.first, lineOf(f));
			if (!kv.first.IsScalar())
				fail(
				    line, f.path,
				    "expected a key name, got " + describe(kv.first));
			const std::string key = kv.first.Scalar();
			if (std::find(allowed.begin(), allowed.end(), key) == allowed.end())
				fail(
				    line, child(f.path, key),
				    "unknown key (allowed: " + joined(allowed, ", ") + ")");
			if (!seen.insert(key).second)
				fail(line, child(f.path, key), "duplicate key");
		}
	}

	std::string text(const Field& f) const
	{
		if (!f.present() || !f.node.IsScalar())
			fail(f, "expected a name, got " + describe(f.node));
		return f.node.Scalar();
	}

	double number(const Field& f) const
	{
		// Quoted scalars (tag "!") are strings, not numbers.
		if (!f.present() || !f.node.IsScalar() || f.node.Tag() == "!")
			fail(f, "expected a number, got " + describe(f.node));
		double v = 0;
		if (!YAML::convert<double>::decode(f.node, v) || !std::isfinite(v))
			fail(f, "expected a number, got " + describe(f.node));
		return v;
	}

	double positive(const Field& f) const
	{
		const double v = number(f);
		if (!(v > 0)) fail(f, "must be > 0, got " + fmt(v));
		return v;
	}

	double nonNegative(const Field& f) const
	{
		const double v = number(f);
		if (!(v >= 0)) fail(f, "must be >= 0, got " + fmt(v));
		return v;
	}

	/** A length `v` read from `f`, at most kMaxLength. */
	double bounded(const Field& f, double v) const
	{
		if (v > kMaxLength)
			fail(f, "must be at most " + fmt(kMaxLength) + " m, got " + fmt(v));
		return v;
	}

	double length(const Field& f) const { return bounded(f, positive(f)); }

	double nonNegativeLength(const Field& f) const
	{
		return bounded(f, nonNegative(f));
	}

	/** A coordinate `v` read from `f`, within +-kMaxCoordinate. */
	double coordinate(const Field& f, double v) const
	{
		if (std::abs(v) > kMaxCoordinate)
			fail(
			    f, "must lie within +-" + fmt(kMaxCoordinate) + " m, got " +
			           fmt(v));
		return v;
	}

	/** `count` numbers of the list `f`, the first `coords` of them
	 * coordinates. */
	std::vector<double> coordinates(
	    const Field& f, std::size_t count, std::size_t coords) const
	{
		const auto v = numbers(f, count);
		for (std::size_t i = 0; i < coords; i++)
			coordinate(element(f, i), v[i]);
		return v;
	}

	int integer(const Field& f) const
	{
		const double v = number(f);
		if (v != std::floor(v) || std::abs(v) > 1e9)
			fail(f, "expected an integer, got " + fmt(v));
		return static_cast<int>(v);
	}

	std::vector<double> numbers(const Field& f, std::size_t count) const
	{
		const std::string expected = std::to_string(count) + " numbers";
		if (!f.present() || !f.node.IsSequence())
			fail(
			    f,
			    "expected a list of " + expected + ", got " + describe(f.node));
		if (f.node.size() != count)
			fail(
			    f, "expected " + expected + ", got " +
			           std::to_string(f.node.size()));
		std::vector<double> v;
		for (std::size_t i = 0; i < count; i++)
			v.push_back(number(element(f, i)));
		return v;
	}

	mrpt::math::TPoint3D point3(const Field& f) const
	{
		const auto v = coordinates(f, 3, 3);
		return {v[0], v[1], v[2]};
	}

	mrpt::math::TPoint2D point2(const Field& f) const
	{
		const auto v = coordinates(f, 2, 2);
		return {v[0], v[1]};
	}

	/** Optional yaw in degrees (default 0), returned in radians. */
	double yaw(const Field& map) const
	{
		const Field y = field(map, "yaw");
		return y.present() ? number(y) * kDegToRad : 0.0;
	}

	/** Reads [min, max, step] in degrees, within [-limit, limit]. */
	void angleRange(
	    const Field& f, double limitDeg, double& lo, double& hi,
	    double& step) const
	{
		const auto v = numbers(f, 3);
		if (!(v[0] < v[1]))
			fail(
			    f, "min must be < max, got min " + fmt(v[0]) + ", max " +
			           fmt(v[1]));
		if (!(v[2] >= kMinAngleStepDeg))
			fail(
			    f, "step must be >= " + fmt(kMinAngleStepDeg) + " deg, got " +
			           fmt(v[2]));
		if (v[0] < -limitDeg || v[1] > limitDeg)
			fail(
			    f, "must lie within [" + fmt(-limitDeg) + ", " + fmt(limitDeg) +
			           "] deg, got [" + fmt(v[0]) + ", " + fmt(v[1]) + "]");
		lo = v[0] * kDegToRad;
		hi = v[1] * kDegToRad;
		step = v[2] * kDegToRad;
	}

	Label label(const Field& f) const
	{
		const std::string name = text(f);
		Label lab = Label::Unknown;
		try
		{
			lab = labelFromName(name);
		}
		catch (const UnknownLabelError&)
		{
			fail(
			    f, "unknown label '" + name +
			           "' (known: " + labelNamesForObjects() + ")");
		}
		if (lab == Label::Unknown)
			fail(f, "label 'unknown' is not allowed for an object");
		return lab;
	}

	BoxShape box(const Field& f) const
	{
		expectMap(f);
		checkKeys(f, {"center", "size", "yaw"});
		BoxShape b;
		b.center = point3(required(f, "center"));
		const Field size = required(f, "size");
		const auto s = numbers(size, 3);
		for (std::size_t i = 0; i < 3; i++)
		{
			if (!(s[i] > 0))
				fail(element(size, i), "must be > 0, got " + fmt(s[i]));
			bounded(element(size, i), s[i]);
		}
		b.size = {s[0], s[1], s[2]};
		b.yaw = yaw(f);
		return b;
	}

	CylinderShape cylinder(const Field& f) const
	{
		expectMap(f);
		checkKeys(f, {"center", "radius", "height"});
		CylinderShape c;
		c.center = point3(required(f, "center"));
		c.radius = length(required(f, "radius"));
		c.height = length(required(f, "height"));
		return c;
	}

	StairsShape stairs(const Field& f) const
	{
		expectMap(f);
		checkKeys(f, {"origin", "yaw", "steps", "rise", "run", "width"});
		StairsShape s;
		s.origin = point2(required(f, "origin"));
		s.yaw = yaw(f);
		const Field steps = required(f, "steps");
		s.steps = integer(steps);
		if (s.steps < 1 || s.steps > kMaxSteps)
			fail(
			    steps, "must be in [1, " + std::to_string(kMaxSteps) +
			               "], got " + std::to_string(s.steps));
		s.rise = length(required(f, "rise"));
		s.run = length(required(f, "run"));
		s.width = length(required(f, "width"));
		return s;
	}

	TerrainShape terrain(const Field& f) const
	{
		expectMap(f);
		checkKeys(f, {"polygon", "roughness"});
		TerrainShape t;
		const Field poly = required(f, "polygon");
		expectList(poly);
		if (poly.node.size() < 3)
			fail(
			    poly, "expected at least 3 vertices, got " +
			              std::to_string(poly.node.size()));
		for (std::size_t i = 0; i < poly.node.size(); i++)
			t.polygon.push_back(point2(element(poly, i)));
		if (!(polygonArea(t.polygon) > 1e-9))
			fail(poly, "degenerate polygon (zero area)");
		t.roughness = nonNegativeLength(required(f, "roughness"));
		return t;
	}

	/** The one primitive of the map `owner` among kPrimitiveKeys (and
	 * `parts` when allowed); exactly one must be present. */
	std::string shapeKey(const Field& owner, bool allowParts) const
	{
		std::vector<std::string> candidates = kPrimitiveKeys;
		if (allowParts) candidates.push_back("parts");
		std::vector<std::string> present;
		for (const auto& k : candidates)
			if (owner.node[k].IsDefined()) present.push_back(k);
		const std::string list = joined(candidates, ", ");
		if (present.empty())
			fail(owner, "missing shape: expected one of " + list);
		if (present.size() > 1)
			fail(
			    owner, "expected exactly one of " + list + ", got " +
			               joined(present, " and "));
		return present.front();
	}

	ScenePrimitive primitive(const Field& owner, const std::string& key) const
	{
		const Field f = field(owner, key);
		if (key == "box") return box(f);
		if (key == "cylinder") return cylinder(f);
		if (key == "stairs") return stairs(f);
		return terrain(f);
	}

	SceneObject object(const Field& f) const
	{
		expectMap(f);
		std::vector<std::string> allowed = {"label"};
		allowed.insert(
		    allowed.end(), kPrimitiveKeys.begin(), kPrimitiveKeys.end());
		allowed.push_back("parts");
		checkKeys(f, allowed);
		SceneObject o;
		o.line = lineOf(f);
		o.label = label(required(f, "label"));
		const std::string key = shapeKey(f, true);
		if (key != "parts")
		{
			o.parts.push_back(primitive(f, key));
			return o;
		}
		const Field parts = field(f, "parts");
		expectList(parts);
		if (parts.node.size() == 0)
			fail(parts, "expected at least 1 part, got 0");
		for (std::size_t i = 0; i < parts.node.size(); i++)
		{
			const Field p = element(parts, i);
			expectMap(p);
			checkKeys(p, kPrimitiveKeys);
			o.parts.push_back(primitive(p, shapeKey(p, false)));
		}
		return o;
	}

	void sensor(const Field& f, SensorSpec& s) const
	{
		expectMap(f);
		checkKeys(f, {"mount", "phi", "theta", "max_range", "range_noise"});
		if (const Field v = field(f, "mount"); v.present()) s.mount = point3(v);
		if (const Field v = field(f, "phi"); v.present())
			angleRange(v, 180, s.phiMin, s.phiMax, s.phiStep);
		if (const Field v = field(f, "theta"); v.present())
			angleRange(v, 90, s.thetaMin, s.thetaMax, s.thetaStep);
		if (const Field v = field(f, "max_range"); v.present())
			s.maxRange = length(v);
		if (const Field v = field(f, "range_noise"); v.present())
			s.rangeNoise = nonNegativeLength(v);
	}

	void odometry(const Field& f, OdometrySpec& o) const
	{
		expectMap(f);
		checkKeys(
		    f, {"trans_noise", "rot_noise_deg_per_m", "rot_bias_deg_per_m"});
		if (const Field v = field(f, "trans_noise"); v.present())
			o.transNoise = nonNegative(v);
		if (const Field v = field(f, "rot_noise_deg_per_m"); v.present())
			o.rotNoisePerM = nonNegative(v) * kDegToRad;
		if (const Field v = field(f, "rot_bias_deg_per_m"); v.present())
			o.rotBiasPerM = number(v) * kDegToRad;
	}
};

Scene Parser::scene(const YAML::Node& rootNode) const
{
	const Field root{rootNode, "", 1};
	if (!rootNode.IsDefined() || !rootNode.IsMap())
		fail(
		    root, "expected a scene map (keys: " + joined(kSceneKeys, ", ") +
		              "), got " + describe(rootNode));
	checkKeys(root, kSceneKeys);
	Scene sc;

	const Field name = required(root, "name");
	sc.name = text(name);
	const bool nameOk =
	    !sc.name.empty() && sc.name[0] != '.' &&
	    std::all_of(
	        sc.name.begin(), sc.name.end(),
	        [](unsigned char c)
	        { return std::isalnum(c) || c == '_' || c == '-' || c == '.'; });
	if (!nameOk)
		fail(
		    name,
		    "'" + sc.name +
		        "' is not a valid file name (use letters, digits, _ - .)");

	const Field bounds = required(root, "bounds");
	const auto b = coordinates(bounds, 4, 4);
	sc.bounds = {b[0], b[1], b[2], b[3]};
	if (!(b[2] > b[0]) || !(b[3] > b[1]))
		fail(
		    bounds, "expected xmin < xmax and ymin < ymax, got [" + fmt(b[0]) +
		                ", " + fmt(b[1]) + ", " + fmt(b[2]) + ", " + fmt(b[3]) +
		                "]");

	if (const Field c = field(root, "ceiling_height"); c.present())
		sc.ceilingHeight = length(c);

	if (const Field objs = field(root, "objects"); objs.present())
	{
		expectList(objs);
		if (objs.node.size() > kMaxObjects)
			fail(
			    element(objs, kMaxObjects),
			    "too many objects: " + std::to_string(objs.node.size()) +
			        ", at most " + std::to_string(kMaxObjects) +
			        " (instance ids are stored in a byte)");
		for (std::size_t i = 0; i < objs.node.size(); i++)
		{
			SceneObject o = object(element(objs, i));
			o.id = static_cast<int>(i) + 1;
			sc.objects.push_back(std::move(o));
		}
	}

	if (const Field s = field(root, "sensor"); s.present())
		sensor(s, sc.sensor);
	if (const Field o = field(root, "odometry"); o.present())
		odometry(o, sc.odometry);

	const Field traj = required(root, "trajectory");
	expectList(traj);
	if (traj.node.size() == 0) fail(traj, "expected at least 1 pose, got 0");
	for (std::size_t i = 0; i < traj.node.size(); i++)
	{
		const Field pose = element(traj, i);
		const auto p = coordinates(pose, 3, 2);
		if (!sc.bounds.contains(p[0], p[1]))
			fail(
			    pose, "pose (" + fmt(p[0]) + ", " + fmt(p[1]) +
			              ") is outside the bounds");
		if (const auto o = sc.obstacleAt(p[0], p[1]))
			fail(
			    pose, "pose (" + fmt(p[0]) + ", " + fmt(p[1]) + ") is inside " +
			              item("objects", *o) + " (" +
			              labelName(sc.objects[*o].label) + ", line " +
			              std::to_string(sc.objects[*o].line) + ")");
		sc.trajectory.emplace_back(p[0], p[1], p[2] * kDegToRad);
	}
	return sc;
}

/** Where the YAML documents of a text start (their first node), the first
 * `max` of them: yaml-cpp 0.7's LoadAll() never ends on some malformed text
 * (a stray '}' starts an empty document again and again). */
class DocumentStarts : public YAML::EventHandler
{
public:
	static std::vector<YAML::Mark> of(const std::string& text, std::size_t max)
	{
		std::istringstream in(text);
		YAML::Parser p(in);
		DocumentStarts h;
		while (h.m_marks.size() < max && p.HandleNextDocument(h))
		{
		}
		return h.m_marks;
	}

	void OnDocumentStart(const YAML::Mark& m) override
	{
		m_marks.push_back(m);
		m_fresh = true;
	}
	void OnDocumentEnd() override {}
	void OnNull(const YAML::Mark& m, YAML::anchor_t) override { node(m); }
	void OnAlias(const YAML::Mark& m, YAML::anchor_t) override { node(m); }
	void OnScalar(
	    const YAML::Mark& m, const std::string&, YAML::anchor_t,
	    const std::string&) override
	{
		node(m);
	}
	void OnSequenceStart(
	    const YAML::Mark& m, const std::string&, YAML::anchor_t,
	    YAML::EmitterStyle::value) override
	{
		node(m);
	}
	void OnSequenceEnd() override {}
	void OnMapStart(
	    const YAML::Mark& m, const std::string&, YAML::anchor_t,
	    YAML::EmitterStyle::value) override
	{
		node(m);
	}
	void OnMapEnd() override {}

private:
	void node(const YAML::Mark& m)
	{
		if (m_fresh && !m.is_null()) m_marks.back() = m;
		m_fresh = false;
	}
	std::vector<YAML::Mark> m_marks;
	bool m_fresh = false;
};

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
	YAML::Node doc;
	try
	{
		const auto starts = DocumentStarts::of(yamlText, 2);
		if (starts.empty()) parser.fail(1, "", "empty scene file");
		if (starts.size() > 1)
			parser.fail(
			    starts[1].line + 1, "",
			    "expected one YAML document, a second one starts here");
		doc = YAML::Load(yamlText);
	}
	catch (const YAML::Exception& e)
	{
		parser.fail(
		    e.mark.is_null() ? 0 : e.mark.line + 1, "",
		    "YAML syntax error: " + e.msg);
	}
	try
	{
		return parser.scene(doc);
	}
	catch (const YAML::Exception& e)
	{
		// Not expected: the parser checks types before converting.
		parser.fail(
		    e.mark.is_null() ? 0 : e.mark.line + 1, "", "YAML error: " + e.msg);
	}
}

}  // namespace semnav
