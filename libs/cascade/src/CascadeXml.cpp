/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/cascade/CascadeError.h>
#include <semnav/cascade/CascadeXml.h>
#include <semnav/common/AtomicFile.h>

#include <fstream>
#include <opencv2/core.hpp>
#include <sstream>

namespace semnav
{
namespace
{
// Node names of OpenCV's cascade format (objdetect's CC_* constants).
constexpr const char* kStageType = "stageType";
constexpr const char* kFeatureType = "featureType";
constexpr const char* kHeight = "height";
constexpr const char* kWidth = "width";
constexpr const char* kStageParams = "stageParams";
constexpr const char* kFeatureParams = "featureParams";
constexpr const char* kStageNum = "stageNum";
constexpr const char* kStages = "stages";
constexpr const char* kFeatures = "features";
constexpr const char* kWeakCount = "maxWeakCount";
constexpr const char* kStageThreshold = "stageThreshold";
constexpr const char* kWeakClassifiers = "weakClassifiers";
constexpr const char* kInternalNodes = "internalNodes";
constexpr const char* kLeafValues = "leafValues";
constexpr const char* kRects = "rects";
constexpr const char* kTilted = "tilted";
constexpr const char* kNote = "semnavNote";

std::string firstLineOf(const std::string& s)
{
	std::istringstream in(s);
	std::string line;
	while (std::getline(in, line))
		if (line.find_first_not_of(" \t\r") != std::string::npos) return line;
	return s;
}
}  // namespace

std::string CascadeXml::toString(const HaarCascade& c)
{
	c.validate();
	try
	{
		cv::FileStorage fs(
		    ".xml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY);
		// Same layout as opencv_traincascade's CvCascadeClassifier::save.
		fs << "cascade"
		   << "{";
		fs << kStageType << "BOOST";
		fs << kFeatureType << "HAAR";
		fs << kHeight << c.windowSize.height;
		fs << kWidth << c.windowSize.width;
		fs << kStageParams << "{";
		fs << "boostType" << c.params.boostType;
		fs << "minHitRate" << c.params.minHitRate;
		fs << "maxFalseAlarm" << c.params.maxFalseAlarm;
		fs << "weightTrimRate" << c.params.weightTrimRate;
		fs << "maxDepth" << c.params.maxDepth;
		fs << kWeakCount << c.params.maxWeakCount;
		fs << "}";
		fs << kFeatureParams << "{";
		fs << "maxCatCount" << 0;
		fs << "featSize" << 1;
		fs << "mode" << haarModeName(c.params.mode);
		fs << "}";
		fs << kStageNum << static_cast<int>(c.stages.size());
		fs << kStages << "[";
		for (const auto& stage : c.stages)
		{
			fs << "{";
			fs << kWeakCount << static_cast<int>(stage.stumps.size());
			fs << kStageThreshold << static_cast<double>(stage.threshold);
			fs << kWeakClassifiers << "[";
			for (const auto& s : stage.stumps)
			{
				fs << "{";
				// Root node: left child = leaf 0, right child = leaf -1.
				fs << kInternalNodes << "[:" << 0 << -1 << s.featureIdx
				   << static_cast<double>(s.threshold) << "]";
				fs << kLeafValues << "[:" << static_cast<double>(s.left)
				   << static_cast<double>(s.right) << "]";
				fs << "}";
			}
			fs << "]";
			fs << "}";
		}
		fs << "]";
		fs << kFeatures << "[";
		for (const auto& f : c.features)
		{
			fs << "{";
			fs << kRects << "[";
			for (int i = 0; i < f.count; i++)
			{
				const auto& r = f.rects[i];
				fs << "[:" << r.rect.x << r.rect.y << r.rect.width
				   << r.rect.height << static_cast<double>(r.weight) << "]";
			}
			fs << "]";
			fs << kTilted << (f.tilted ? 1 : 0);
			fs << "}";
		}
		fs << "]";
		if (!c.note.empty()) fs << kNote << c.note;
		fs << "}";
		return fs.releaseAndGetString();
	}
	catch (const cv::Exception& e)
	{
		throw CascadeError("cannot format cascade XML: " + e.msg);
	}
}

void CascadeXml::writeFile(const std::string& path, const HaarCascade& cascade)
{
	writeFileAtomically(path, toString(cascade));
}

namespace
{
/** Reading helpers that throw CascadeError with the node's path. */
class Reader
{
public:
	explicit Reader(std::string source) : m_source(std::move(source)) {}

	[[noreturn]] void fail(
	    const std::string& where, const std::string& what) const
	{
		throw CascadeError(
		    m_source + ": " + (where.empty() ? "" : where + ": ") + what);
	}
	const cv::FileNode& need(
	    const cv::FileNode& n, const std::string& where) const
	{
		if (n.empty() || n.isNone()) fail(where, "missing");
		return n;
	}
	double number(const cv::FileNode& n, const std::string& where) const
	{
		need(n, where);
		if (!n.isInt() && !n.isReal()) fail(where, "expected a number");
		return static_cast<double>(n);
	}
	int integer(const cv::FileNode& n, const std::string& where) const
	{
		need(n, where);
		if (!n.isInt()) fail(where, "expected an integer");
		return static_cast<int>(n);
	}
	std::string text(const cv::FileNode& n, const std::string& where) const
	{
		need(n, where);
		if (!n.isString()) fail(where, "expected a string");
		return static_cast<std::string>(n);
	}
	std::vector<double> numbers(
	    const cv::FileNode& n, const std::string& where) const
	{
		need(n, where);
		if (!n.isSeq()) fail(where, "expected a list of numbers");
		std::vector<double> v;
		for (const auto& e : n)
		{
			if (!e.isInt() && !e.isReal())
				fail(where, "expected a list of numbers");
			v.push_back(static_cast<double>(e));
		}
		return v;
	}
	const std::string& source() const { return m_source; }

private:
	std::string m_source;
};

/** The window size and the stage and feature types (BOOST, HAAR). */
void parseHeader(const cv::FileNode& root, const Reader& rd, HaarCascade& c)
{
	if (root.empty() || !root.isMap())
		rd.fail("", "no cascade map at the top level");
	const std::string stageType = rd.text(root[kStageType], kStageType);
	if (stageType != "BOOST")
		rd.fail(kStageType, "'" + stageType + "' is not BOOST");
	const std::string featureType = rd.text(root[kFeatureType], kFeatureType);
	if (featureType != "HAAR")
		rd.fail(kFeatureType, "'" + featureType + "' is not HAAR");
	c.windowSize.width = rd.integer(root[kWidth], kWidth);
	c.windowSize.height = rd.integer(root[kHeight], kHeight);
	if (c.windowSize.width < 3 || c.windowSize.height < 3 ||
	    c.windowSize.width > 1000 || c.windowSize.height > 1000)
		rd.fail("width/height", "window size out of range [3, 1000]");
}

/** stageParams (optional) and featureParams. */
void parseParams(const cv::FileNode& root, const Reader& rd, HaarCascade& c)
{
	const cv::FileNode sp = root[kStageParams];
	if (!sp.empty() && sp.isMap())
	{
		if (sp["boostType"].isString())
			c.params.boostType = static_cast<std::string>(sp["boostType"]);
		if (!sp["minHitRate"].empty())
			c.params.minHitRate = rd.number(sp["minHitRate"], "minHitRate");
		if (!sp["maxFalseAlarm"].empty())
			c.params.maxFalseAlarm =
			    rd.number(sp["maxFalseAlarm"], "maxFalseAlarm");
		if (!sp["weightTrimRate"].empty())
			c.params.weightTrimRate =
			    rd.number(sp["weightTrimRate"], "weightTrimRate");
		if (!sp["maxDepth"].empty())
			c.params.maxDepth = rd.integer(sp["maxDepth"], "maxDepth");
		if (!sp[kWeakCount].empty())
			c.params.maxWeakCount = rd.integer(sp[kWeakCount], kWeakCount);
	}
	const cv::FileNode fp = rd.need(root[kFeatureParams], kFeatureParams);
	if (!fp["maxCatCount"].empty() &&
	    rd.integer(fp["maxCatCount"], "maxCatCount") != 0)
		rd.fail(
		    "featureParams.maxCatCount",
		    "categorical features are not HAAR features");
	if (fp["mode"].isString())
	{
		try
		{
			c.params.mode =
			    haarModeFromName(static_cast<std::string>(fp["mode"]));
		}
		catch (const CascadeError& e)
		{
			rd.fail("featureParams.mode", e.what());
		}
	}
}

/** Weak classifier `wn` (a stump), `w` naming it in errors. */
HaarCascade::Stump parseStump(
    const cv::FileNode& wn, const std::string& w, const Reader& rd)
{
	const auto nodes = rd.numbers(wn[kInternalNodes], w + ": internalNodes");
	const auto leaves = rd.numbers(wn[kLeafValues], w + ": leafValues");
	if (nodes.size() != 4 || leaves.size() != 2)
		rd.fail(
		    w,
		    "only stumps (internalNodes of 4 numbers, 2 leafValues) "
		    "are supported, got " +
		        std::to_string(nodes.size()) + " and " +
		        std::to_string(leaves.size()));
	if (nodes[0] > 0 || nodes[1] > 0)
		rd.fail(w, "internal node children must be leaves (<= 0)");
	HaarCascade::Stump s;
	s.featureIdx = static_cast<int>(nodes[2]);
	if (static_cast<double>(s.featureIdx) != nodes[2])
		rd.fail(w, "feature index must be an integer");
	s.threshold = static_cast<float>(nodes[3]);
	// OpenCV maps node children to leaves in order: leaf 0 is taken
	// for value < threshold, leaf 1 otherwise (Data::read builds
	// Stump(featureIdx, threshold, leaves[0], leaves[1])).
	s.left = static_cast<float>(leaves[0]);
	s.right = static_cast<float>(leaves[1]);
	return s;
}

/** The stages, checked against stageNum. */
void parseStages(const cv::FileNode& root, const Reader& rd, HaarCascade& c)
{
	const cv::FileNode stages = rd.need(root[kStages], kStages);
	if (!stages.isSeq()) rd.fail(kStages, "expected a list of stages");
	int si = 0;
	for (const auto& sn : stages)
	{
		const std::string where = "stage " + std::to_string(si);
		if (!sn.isMap()) rd.fail(where, "expected a map");
		HaarCascade::Stage stage;
		stage.threshold = static_cast<float>(
		    rd.number(sn[kStageThreshold], where + ": " + kStageThreshold));
		const cv::FileNode weak =
		    rd.need(sn[kWeakClassifiers], where + ": " + kWeakClassifiers);
		if (!weak.isSeq() || weak.size() == 0)
			rd.fail(where, "weakClassifiers must be a non-empty list");
		int wi = 0;
		for (const auto& wn : weak)
		{
			const std::string w =
			    where + ", weak classifier " + std::to_string(wi);
			stage.stumps.push_back(parseStump(wn, w, rd));
			wi++;
		}
		c.stages.push_back(std::move(stage));
		si++;
	}
	if (c.stages.empty()) rd.fail(kStages, "no stages");
	const cv::FileNode sn = root[kStageNum];
	if (!sn.empty() &&
	    rd.integer(sn, kStageNum) != static_cast<int>(c.stages.size()))
		rd.fail(
		    kStageNum, "says " + std::to_string(static_cast<int>(sn)) +
		                   " but there are " + std::to_string(c.stages.size()) +
		                   " stages");
}

/** The features, each inside the window. */
void parseFeatures(const cv::FileNode& root, const Reader& rd, HaarCascade& c)
{
	const cv::FileNode features = rd.need(root[kFeatures], kFeatures);
	if (!features.isSeq()) rd.fail(kFeatures, "expected a list");
	int fi = 0;
	for (const auto& fn : features)
	{
		const std::string where = "feature " + std::to_string(fi);
		const cv::FileNode rects = rd.need(fn[kRects], where + ": rects");
		if (!rects.isSeq() || rects.size() < 2 || rects.size() > 3)
			rd.fail(where, "rects must list 2 or 3 rectangles");
		HaarFeature f;
		for (const auto& rn : rects)
		{
			const auto v = rd.numbers(rn, where + ": rect");
			if (v.size() != 5)
				rd.fail(where, "a rect must be 'x y width height weight'");
			auto& r = f.rects[f.count++];
			r.rect = cv::Rect(
			    static_cast<int>(v[0]), static_cast<int>(v[1]),
			    static_cast<int>(v[2]), static_cast<int>(v[3]));
			r.weight = static_cast<float>(v[4]);
		}
		const cv::FileNode t = fn[kTilted];
		f.tilted = !t.empty() && rd.integer(t, where + ": tilted") != 0;
		if (!f.fitsIn(c.windowSize))
			rd.fail(where, "a rectangle leaves the window");
		c.features.push_back(f);
		fi++;
	}
}

HaarCascade parse(const cv::FileNode& root, const Reader& rd)
{
	HaarCascade c;
	parseHeader(root, rd, c);
	parseParams(root, rd, c);
	parseStages(root, rd, c);
	parseFeatures(root, rd, c);
	if (root[kNote].isString()) c.note = static_cast<std::string>(root[kNote]);
	try
	{
		c.validate();
	}
	catch (const CascadeError& e)
	{
		rd.fail("", e.what());
	}
	return c;
}
}  // namespace

HaarCascade CascadeXml::fromString(
    const std::string& xml, const std::string& source)
{
	const Reader rd(source);
	if (xml.find_first_not_of(" \t\r\n") == std::string::npos)
		rd.fail("", "empty file");
	// OpenCV's XML parser dereferences null on a NUL byte (4.6).
	const std::size_t nul = xml.find('\0');
	if (nul != std::string::npos)
		rd.fail("", "not XML: a NUL byte at byte " + std::to_string(nul));
	try
	{
		cv::FileStorage fs(
		    xml, cv::FileStorage::READ | cv::FileStorage::MEMORY |
		             cv::FileStorage::FORMAT_XML);
		if (!fs.isOpened()) rd.fail("", "not a readable XML file");
		return parse(fs.getFirstTopLevelNode(), rd);
	}
	catch (const cv::Exception& e)
	{
		rd.fail("", "not valid cascade XML (" + firstLineOf(e.err) + ")");
	}
}

HaarCascade CascadeXml::readFile(const std::string& path)
{
	std::ifstream in(path, std::ios::binary);
	if (!in) throw CascadeError("cannot open cascade file " + path);
	std::ostringstream ss;
	ss << in.rdbuf();
	return fromString(ss.str(), path);
}

}  // namespace semnav
