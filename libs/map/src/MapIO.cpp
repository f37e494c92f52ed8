/* semnav: semantic navigation from tilting-laser sweeps */
#include <fcntl.h>
#include <octomap/OcTree.h>
#include <semnav/common/AtomicFile.h>
#include <semnav/common/Error.h>
#include <semnav/common/StagedDirectory.h>
#include <semnav/map/MapIO.h>
#include <semnav/map/MapRenderer.h>
#include <sys/stat.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <opencv2/imgcodecs.hpp>
#include <set>
#include <sstream>

#include "LayerImage.h"
#include "QuietStderr.h"

namespace semnav
{
namespace fs = std::filesystem;

namespace
{
/** Roughness bound: 1 plus room for float rounding of the means. */
constexpr float kRoughnessBound = 1.001f;
constexpr int kFormatVersion = 1;
/** The largest map side a directory may hold (819 m at 5 cm): bounds what
 * a corrupt map.yaml or image header can make the loader allocate. */
constexpr int kMaxSide = 1 << 14;

/** Layer vector -> image with map_server orientation (row 0 = top). */
template <typename T>
cv::Mat toImage(
    const GridGeometry& g, int type, const std::vector<float>& v,
    T (*conv)(float))
{
	cv::Mat img(std::max(g.rows, 1), std::max(g.cols, 1), type, cv::Scalar(0));
	for (int cy = 0; cy < g.rows; cy++)
		for (int cx = 0; cx < g.cols; cx++)
			img.at<T>(g.rows - 1 - cy, cx) = conv(v[g.index(cy, cx)]);
	return img;
}

void writeImage(const std::string& path, const cv::Mat& img)
{
	std::vector<uchar> buf;
	const std::string ext = fs::path(path).extension().string();
	if (!cv::imencode(ext, img, buf)) throw IoError("cannot encode " + path);
	writeFileAtomically(path, std::string(buf.begin(), buf.end()));
}

/** The files of one map directory as it was when opened: a save that
 * swaps a new directory in meanwhile (StagedDirectory) does not mix its
 * files into this read; replaced() then says so and load() reads again. */
class MapDirectory
{
public:
	explicit MapDirectory(const std::string& dir) : m_dir(dir)
	{
		m_fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
		if (m_fd < 0)
		{
			const std::string staged = StagedDirectory::interruptedSave(dir);
			if (!staged.empty())
				throw IoError(
				    "map directory " + dir +
				    " is missing: a save was interrupted; the complete new "
				    "map is in " +
				    staged + " (mv it to " + dir + ")");
			throw IoError("not a map directory (no map.yaml): " + dir);
		}
		::fstat(m_fd, &m_stat);
	}
	~MapDirectory() { ::close(m_fd); }
	MapDirectory(const MapDirectory&) = delete;
	MapDirectory& operator=(const MapDirectory&) = delete;

	std::string path(const std::string& rel) const
	{
		return (fs::path(m_dir) / rel).string();
	}

	bool has(const std::string& rel) const
	{
		struct stat st;
		return ::fstatat(m_fd, rel.c_str(), &st, 0) == 0;
	}

	/** The bytes of `rel`; throws IoError when it is missing. */
	std::string read(const std::string& rel) const
	{
		const int fd = ::openat(m_fd, rel.c_str(), O_RDONLY | O_CLOEXEC);
		if (fd < 0) throw IoError("map file missing: " + path(rel));
		std::string bytes;
		char buf[65536];
		ssize_t n;
		while ((n = ::read(fd, buf, sizeof(buf))) > 0)
			bytes.append(buf, static_cast<std::size_t>(n));
		::close(fd);
		if (n < 0) throw IoError("cannot read " + path(rel));
		return bytes;
	}

	/** The path now names another directory (a save swapped it). */
	bool replaced() const
	{
		struct stat now;
		return ::stat(m_dir.c_str(), &now) != 0 ||
		       now.st_ino != m_stat.st_ino || now.st_dev != m_stat.st_dev;
	}

private:
	std::string m_dir;
	int m_fd = -1;
	struct stat m_stat = {};
};

cv::Mat readImage(
    const MapDirectory& d, const std::string& rel, int type,
    const GridGeometry& g)
{
	return decodeLayerImage(
	    d.read(rel), d.path(rel), type, std::max(g.cols, 1),
	    std::max(g.rows, 1));
}

/** A float layer under layers/, its values checked: log-odds are int8,
 * roughness is NaN where nothing was seen and otherwise a mean of normals'
 * dot products, in [-1, 1] (negative at edges and corners), every other
 * layer (labels, costs, ids, counts, and any added) is finite and >= 0. */
cv::Mat readLayer(
    const MapDirectory& d, const std::string& name, const GridGeometry& g)
{
	const std::string rel = "layers/" + name + ".pfm";
	const cv::Mat img = readImage(d, rel, CV_32FC1, g);
	LayerRange range;
	if (name == "occupancy_logodds")
		range = {-128.0f, 127.0f, false};
	else if (name == "roughness")
		range = {-kRoughnessBound, kRoughnessBound, true};
	checkLayerValues(img, d.path(rel), range);
	return img;
}

template <typename T>
std::vector<float> fromImage(const GridGeometry& g, const cv::Mat& img)
{
	std::vector<float> v(g.cellCount());
	for (int cy = 0; cy < g.rows; cy++)
		for (int cx = 0; cx < g.cols; cx++)
			v[g.index(cy, cx)] =
			    static_cast<float>(img.at<T>(g.rows - 1 - cy, cx));
	return v;
}

std::string where(
    const std::string& file, const YAML::Node& n, const std::string& key)
{
	return file + ":" + std::to_string(n.Mark().line + 1) + ": " + key;
}

YAML::Node need(
    const YAML::Node& parent, const std::string& key, const std::string& file,
    const std::string& path)
{
	const YAML::Node n = parent[key];
	if (!n) throw IoError(where(file, parent, path + key) + ": missing");
	return n;
}

template <typename T>
T as(const YAML::Node& n, const std::string& file, const std::string& key)
{
	try
	{
		return n.as<T>();
	}
	catch (const YAML::Exception&)
	{
		throw IoError(where(file, n, key) + ": bad value");
	}
}

mrpt::math::TPoint3D point3(
    const YAML::Node& n, const std::string& file, const std::string& key)
{
	if (!n.IsSequence() || n.size() != 3)
		throw IoError(where(file, n, key) + ": expected 3 numbers");
	return {
	    as<double>(n[0], file, key), as<double>(n[1], file, key),
	    as<double>(n[2], file, key)};
}

void emitPoint(YAML::Emitter& e, const mrpt::math::TPoint3D& p)
{
	e << YAML::Flow << YAML::BeginSeq << p.x << p.y << p.z << YAML::EndSeq;
}
}  // namespace

namespace
{
/** A layer as saved: the "objects" layer keeps the ids of the objects the
 * map reports (SemanticMap::reported) only; candidates are not saved. */
std::vector<float> savedLayer(const SemanticMap& map, const std::string& name)
{
	std::vector<float> v = map.get(name);
	if (name != "objects") return v;
	std::set<float> reported;
	for (const auto& o : map.instances())
		reported.insert(static_cast<float>(o.id));
	for (auto& id : v)
		if (id != 0 && !reported.count(id)) id = 0;
	return v;
}

/** occupancy.png (map_server trinary), labels.png, objects.png, cost.png
 * and map.png. */
void saveImages(const SemanticMap& map, const fs::path& dir, double L)
{
	const GridGeometry& g = map.geometry();
	cv::Mat occ(
	    std::max(g.rows, 1), std::max(g.cols, 1), CV_8UC1, cv::Scalar(205));
	for (int cy = 0; cy < g.rows; cy++)
		for (int cx = 0; cx < g.cols; cx++)
		{
			uint8_t v = 205;
			switch (map.cellState(cx, cy))
			{
				case SemanticMap::CellState::Occupied:
					v = 0;
					break;
				case SemanticMap::CellState::Free:
					v = 254;
					break;
				default:
					v = 205;
			}
			occ.at<uint8_t>(g.rows - 1 - cy, cx) = v;
		}
	writeImage((dir / "occupancy.png").string(), occ);
	writeImage(
	    (dir / "labels.png").string(),
	    toImage<uint16_t>(
	        g, CV_16UC1, map.get("labels"),
	        [](float f) {
		        return static_cast<uint16_t>(
		            static_cast<uint32_t>(f) & 0xFFFFu);
	        }));
	writeImage(
	    (dir / "objects.png").string(),
	    toImage<uint16_t>(
	        g, CV_16UC1, savedLayer(map, "objects"),
	        [](float f) { return static_cast<uint16_t>(f); }));
	std::vector<float> scaled = map.get("cost");
	for (auto& v : scaled)
		v = static_cast<float>(
		    std::round(std::min<double>(v, L) / L * 65535.0));
	writeImage(
	    (dir / "cost.png").string(),
	    toImage<uint16_t>(
	        g, CV_16UC1, scaled,
	        [](float f) { return static_cast<uint16_t>(f); }));
	writeImage((dir / "map.png").string(), MapRenderer::render(map));
}

/** The exact state (layers/<name>.pfm), and octomap.bt (opens in octovis). */
void saveExactState(const SemanticMap& map, const fs::path& dir)
{
	const GridGeometry& g = map.geometry();
	std::vector<float> logodds(g.cellCount());
	const auto& raw = map.occupancyGrid().getRawMap();
	for (std::size_t i = 0; i < logodds.size(); i++)
		logodds[i] = static_cast<float>(raw[i]);
	writeImage(
	    (dir / "layers" / "occupancy_logodds.pfm").string(),
	    toImage<float>(g, CV_32FC1, logodds, [](float f) { return f; }));
	for (const auto& name : map.layers())
		writeImage(
		    (dir / "layers" / (name + ".pfm")).string(),
		    toImage<float>(
		        g, CV_32FC1, savedLayer(map, name), [](float f) { return f; }));
	writeAtomically(
	    (dir / "octomap.bt").string(),
	    [&](const std::string& tmp)
	    {
		    std::ofstream f(tmp, std::ios::binary);
		    const QuietStderr quiet;
		    if (!f || !map.octree().writeBinaryConst(f))
			    throw IoError("cannot write " + tmp);
	    });
}

void emitObjects(YAML::Emitter& e, const SemanticMap& map)
{
	e << YAML::Key << "objects" << YAML::Value << YAML::BeginSeq;
	for (const auto& o : map.instances())
	{
		e << YAML::BeginMap;
		e << YAML::Key << "id" << YAML::Value << o.id;
		e << YAML::Key << "label" << YAML::Value << labelName(o.label);
		e << YAML::Key << "centroid" << YAML::Value;
		emitPoint(e, o.centroid);
		e << YAML::Key << "extent" << YAML::Value;
		emitPoint(e, o.extent());
		e << YAML::Key << "min" << YAML::Value;
		emitPoint(e, o.minCorner);
		e << YAML::Key << "max" << YAML::Value;
		emitPoint(e, o.maxCorner);
		e << YAML::Key << "observations" << YAML::Value << o.observations;
		e << YAML::Key << "views" << YAML::Value << o.views;
		e << YAML::Key << "shape_score" << YAML::Value << o.bestShapeScore;
		e << YAML::EndMap;
	}
	e << YAML::EndSeq;
}

/** map.yaml: the ROS map_server keys, then semnav's. */
std::string mapYaml(const SemanticMap& map, double L)
{
	const GridGeometry& g = map.geometry();
	YAML::Emitter e;
	e << YAML::BeginMap;
	e << YAML::Key << "image" << YAML::Value << "occupancy.png";
	e << YAML::Key << "resolution" << YAML::Value << g.resolution;
	e << YAML::Key << "origin" << YAML::Value << YAML::Flow << YAML::BeginSeq
	  << g.originX << g.originY << 0.0 << YAML::EndSeq;
	// The image is trinary (0 / 254 / 205): map_server's usual thresholds
	// read it back exactly (205 is p = 0.196, not below free_thresh).
	e << YAML::Key << "occupied_thresh" << YAML::Value << 0.65;
	e << YAML::Key << "free_thresh" << YAML::Value << 0.196;
	e << YAML::Key << "negate" << YAML::Value << 0;
	e << YAML::Key << "semnav" << YAML::Value << YAML::BeginMap;
	e << YAML::Key << "format_version" << YAML::Value << kFormatVersion;
	e << YAML::Key << "size" << YAML::Value << YAML::Flow << YAML::BeginSeq
	  << g.cols << g.rows << YAML::EndSeq;
	e << YAML::Key << "sweeps" << YAML::Value << map.sweepsInserted();
	e << YAML::Key << "lethal_cost" << YAML::Value << L;
	e << YAML::Key << "files" << YAML::Value << YAML::BeginMap;
	e << YAML::Key << "labels" << YAML::Value << "labels.png";
	e << YAML::Key << "objects" << YAML::Value << "objects.png";
	e << YAML::Key << "cost" << YAML::Value << "cost.png";
	e << YAML::Key << "render" << YAML::Value << "map.png";
	e << YAML::Key << "octomap" << YAML::Value << "octomap.bt";
	e << YAML::Key << "occupancy_logodds" << YAML::Value
	  << "layers/occupancy_logodds.pfm";
	e << YAML::EndMap;
	e << YAML::Key << "layers" << YAML::Value << YAML::Flow << YAML::BeginSeq;
	for (const auto& name : map.layers()) e << name;
	e << YAML::EndSeq;
	emitObjects(e, map);
	e << YAML::EndMap;
	e << YAML::EndMap;
	return std::string(e.c_str()) + "\n";
}
}  // namespace

namespace
{
/** The names a map directory holds (MapIO::save replaces no other). */
bool isMapEntry(const std::string& name)
{
	for (const char* n :
	     {"map.yaml", "occupancy.png", "labels.png", "objects.png", "cost.png",
	      "map.png", "octomap.bt", "layers"})
		if (name == n) return true;
	return false;
}
}  // namespace

void MapIO::checkTarget(const std::string& dir)
{
	StagedDirectory::checkReplaceable(dir, isMapEntry);
}

void MapIO::save(const SemanticMap& map, const std::string& dir)
{
	StagedDirectory staged(dir, isMapEntry);
	const fs::path tmp(staged.path());
	createDirectories((tmp / "layers").string());
	const double L = map.costModel().options().lethalCost;
	saveImages(map, tmp, L);
	saveExactState(map, tmp);
	writeFileAtomically((tmp / "map.yaml").string(), mapYaml(map, L));
	staged.commit();
}

namespace
{
/** map.yaml's geometry, checked against the configured resolution. */
GridGeometry readGeometry(
    const YAML::Node& root, const std::string& file, double resolution)
{
	GridGeometry g;
	g.resolution =
	    as<double>(need(root, "resolution", file, ""), file, "resolution");
	if (!(g.resolution > 0) || !std::isfinite(g.resolution))
		throw IoError(
		    where(file, root["resolution"], "resolution") +
		    ": must be a positive number of metres per cell");
	const YAML::Node origin = need(root, "origin", file, "");
	if (!origin.IsSequence() || origin.size() < 2)
		throw IoError(where(file, origin, "origin") + ": expected [x, y, yaw]");
	g.originX = as<double>(origin[0], file, "origin");
	g.originY = as<double>(origin[1], file, "origin");
	const YAML::Node sem = need(root, "semnav", file, "");
	const int version = as<int>(
	    need(sem, "format_version", file, "semnav."), file,
	    "semnav.format_version");
	if (version != kFormatVersion)
		throw IoError(
		    where(file, sem, "semnav.format_version") +
		    ": unsupported version " + std::to_string(version));
	const YAML::Node size = need(sem, "size", file, "semnav.");
	if (!size.IsSequence() || size.size() != 2)
		throw IoError(where(file, size, "semnav.size") + ": expected [sx, sy]");
	g.cols = as<int>(size[0], file, "semnav.size");
	g.rows = as<int>(size[1], file, "semnav.size");
	if (!std::isfinite(g.originX) || !std::isfinite(g.originY))
		throw IoError(where(file, origin, "origin") + ": must be finite");
	if (g.cols < 0 || g.rows < 0 || g.cols > kMaxSide || g.rows > kMaxSide)
		throw IoError(
		    where(file, size, "semnav.size") + ": " + std::to_string(g.cols) +
		    " x " + std::to_string(g.rows) + " cells is no map size (0 to " +
		    std::to_string(kMaxSide) + " a side)");
	if (std::abs(g.resolution - resolution) > 1e-9)
		throw IoError(
		    where(file, root["resolution"], "resolution") +
		    ": map resolution differs from the configured one");
	return g;
}

std::vector<ObjectInstance> readObjects(
    const YAML::Node& sem, const std::string& file)
{
	std::vector<ObjectInstance> objs;
	for (const auto& n : need(sem, "objects", file, "semnav."))
	{
		ObjectInstance o;
		o.id = as<int>(need(n, "id", file, "semnav.objects[]."), file, "id");
		try
		{
			o.label = labelFromName(as<std::string>(
			    need(n, "label", file, "semnav.objects[]."), file, "label"));
		}
		catch (const UnknownLabelError& ex)
		{
			throw IoError(
			    where(file, n, "semnav.objects[].label") + ": " + ex.what());
		}
		o.centroid = point3(
		    need(n, "centroid", file, "semnav.objects[]."), file, "centroid");
		o.minCorner =
		    point3(need(n, "min", file, "semnav.objects[]."), file, "min");
		o.maxCorner =
		    point3(need(n, "max", file, "semnav.objects[]."), file, "max");
		o.observations = as<std::size_t>(
		    need(n, "observations", file, "semnav.objects[]."), file,
		    "observations");
		o.views = n["views"] ? as<std::size_t>(n["views"], file, "views")
		                     : o.observations;
		if (n["shape_score"])
			o.bestShapeScore =
			    as<double>(n["shape_score"], file, "shape_score");
		objs.push_back(o);
	}
	return objs;
}

/** One read of the directory as `d` opened it. */
void loadFrom(const MapDirectory& d, SemanticMap& map)
{
	const std::string file = d.path("map.yaml");
	if (!d.has("map.yaml"))
		throw IoError("not a map directory (no map.yaml): " + d.path(""));
	YAML::Node root;
	try
	{
		root = YAML::Load(d.read("map.yaml"));
	}
	catch (const YAML::Exception& ex)
	{
		throw IoError(
		    file + ":" + std::to_string(ex.mark.line + 1) + ": " + ex.msg);
	}
	if (!root.IsMap()) throw IoError(file + ": not a map.yaml");
	const GridGeometry g = readGeometry(root, file, map.options().resolution);
	const YAML::Node sem = root["semnav"];

	std::map<std::string, std::vector<float>> layers;
	const YAML::Node names = need(sem, "layers", file, "semnav.");
	for (const auto& n : names)
	{
		const std::string name = as<std::string>(n, file, "semnav.layers");
		layers[name] = fromImage<float>(g, readLayer(d, name, g));
	}
	const auto lo = fromImage<float>(g, readLayer(d, "occupancy_logodds", g));
	std::vector<int8_t> logodds(lo.size());
	for (std::size_t i = 0; i < lo.size(); i++)
		logodds[i] = static_cast<int8_t>(lo[i]);
	// The contract images must be there and agree in size.
	readImage(d, "occupancy.png", CV_8UC1, g);
	readImage(d, "labels.png", CV_16UC1, g);

	std::vector<ObjectInstance> objs = readObjects(sem, file);
	const auto sweeps = as<std::size_t>(
	    need(sem, "sweeps", file, "semnav."), file, "semnav.sweeps");
	std::istringstream bt(d.read("octomap.bt"));
	map.restore(g, std::move(layers), logodds, std::move(objs), sweeps);
	bool ok = false;
	{
		const QuietStderr quiet;
		ok = static_cast<bool>(map.octree().readBinary(bt));
	}
	if (!ok) throw IoError("cannot read OctoMap " + d.path("octomap.bt"));
}
}  // namespace

void MapIO::load(const std::string& dir, SemanticMap& map)
{
	// A save may swap the directory while we read it: read again then.
	for (int attempt = 0;; attempt++)
	{
		const MapDirectory d(dir);
		try
		{
			loadFrom(d, map);
			return;
		}
		catch (const IoError&)
		{
			if (attempt >= 3 || !d.replaced()) throw;
		}
	}
}

}  // namespace semnav
