/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/Error.h>
#include <semnav/detection/ShapeVerifier.h>

#include <filesystem>
#include <opencv2/core.hpp>

namespace semnav
{
namespace
{
bool knownFeatureCount(int n)
{
	return !ObjectShape::columnsOf(n).empty();
}

const std::string kFeatureCounts =
    std::to_string(ObjectShape::featureCount(false, false)) + ", " +
    std::to_string(ObjectShape::featureCount(false, true)) + ", " +
    std::to_string(ObjectShape::featureCount(true, false)) + " or " +
    std::to_string(ObjectShape::featureCount(true, true));
}  // namespace

int ShapeVerifier::featureCount() const
{
	return m_forest ? m_forest->getVarCount() : 0;
}

bool ShapeVerifier::readsSteps() const
{
	return !m_columns.empty() && m_columns.back() >= ObjectShape::kStepsAt;
}

ShapeVerifier ShapeVerifier::train(
    const cv::Mat& samples, const cv::Mat& isObject, const TrainParams& params)
{
	if (samples.type() != CV_32F || !knownFeatureCount(samples.cols) ||
	    isObject.type() != CV_32S || isObject.rows != samples.rows)
		throw Error(
		    "ShapeVerifier: samples must be N x " + kFeatureCounts +
		    " ObjectShape features");
	const int objects = cv::countNonZero(isObject);
	if (objects == 0 || objects == samples.rows)
		throw Error(
		    "ShapeVerifier: training needs objects and non-objects (got " +
		    std::to_string(objects) + " of " + std::to_string(samples.rows) +
		    ")");
	cv::theRNG().state = params.seed;
	ShapeVerifier v;
	v.m_forest = cv::ml::RTrees::create();
	v.m_forest->setMaxDepth(params.maxDepth);
	v.m_forest->setMinSampleCount(params.minSampleCount);
	v.m_forest->setCalculateVarImportance(false);
	v.m_forest->setTermCriteria(
	    cv::TermCriteria(cv::TermCriteria::MAX_ITER, params.trees, 0));
	v.m_forest->train(
	    cv::ml::TrainData::create(samples, cv::ml::ROW_SAMPLE, isObject));
	v.flatten();
	return v;
}

ShapeVerifier ShapeVerifier::load(const std::string& path)
{
	if (!std::filesystem::is_regular_file(path))
		throw IoError(path + ": no such shape model");
	ShapeVerifier v;
	try
	{
		v.m_forest = cv::Algorithm::load<cv::ml::RTrees>(path);
	}
	catch (const cv::Exception& e)
	{
		throw IoError(path + ": not a shape model (" + e.err + ")");
	}
	if (!v.m_forest || !v.m_forest->isTrained() ||
	    !v.m_forest->isClassifier() ||
	    !knownFeatureCount(v.m_forest->getVarCount()))
		throw IoError(
		    path + ": not a shape model over " + kFeatureCounts +
		    " ObjectShape features");
	v.flatten();
	return v;
}

void ShapeVerifier::save(const std::string& path) const
{
	if (!m_forest) throw Error("ShapeVerifier: nothing to save");
	// OpenCV compresses by the name's ending: a temporary name with the
	// same ending, then rename.
	const std::filesystem::path target(path);
	const bool gz = target.extension() == ".gz";
	const std::filesystem::path tmp =
	    target.parent_path() /
	    ("." + target.filename().string() + ".tmp" + (gz ? ".xml.gz" : ".xml"));
	try
	{
		cv::FileStorage fs(tmp.string(), cv::FileStorage::WRITE);
		if (!fs.isOpened()) throw IoError(path + ": cannot write");
		fs << m_forest->getDefaultName() << "{";
		m_forest->write(fs);
		fs << "}";
		fs.release();
		std::filesystem::rename(tmp, target);
	}
	catch (const cv::Exception& e)
	{
		std::filesystem::remove(tmp);
		throw IoError(path + ": cannot write (" + e.err + ")");
	}
	catch (const std::filesystem::filesystem_error& e)
	{
		std::filesystem::remove(tmp);
		throw IoError(path + ": cannot write (" + e.what() + ")");
	}
}

void ShapeVerifier::flatten()
{
	// Class labels by class index: row 0 of getVotes.
	cv::Mat votes;
	const ObjectShape::Features zero{};
	m_forest->getVotes(
	    cv::Mat(1, featureCount(), CV_32F, const_cast<float*>(zero.data())),
	    votes, 0);
	m_columns = ObjectShape::columnsOf(featureCount());
	const auto& nodes = m_forest->getNodes();
	const auto& splits = m_forest->getSplits();
	m_roots.clear();
	m_nodes.clear();
	static_assert(
	    ObjectShape::kFeatures < int(kLeaf),
	    "a FlatNode's feature index must not be kLeaf");
	if (nodes.size() > kIndexMask) return;
	m_nodes.reserve(nodes.size());
	// Each tree depth first, left before right; (OpenCV's node, the split
	// whose right child it is, or -1).
	std::vector<std::pair<int, int>> stack;
	for (int root : m_forest->getRoots())
	{
		m_roots.push_back(uint32_t(m_nodes.size()));
		stack.emplace_back(root, -1);
		while (!stack.empty())
		{
			const auto [i, parent] = stack.back();
			stack.pop_back();
			const uint32_t at = uint32_t(m_nodes.size());
			if (parent >= 0) m_nodes[std::size_t(parent)].link |= at;
			const auto& n = nodes.at(std::size_t(i));
			FlatNode& out = m_nodes.emplace_back();
			if (n.split >= 0)
			{
				// RTrees' prediction takes the first split, "<= c" to the
				// left (ordered features only).
				const auto& sp = splits.at(std::size_t(n.split));
				if (sp.varIdx < 0 || sp.varIdx >= featureCount())
					throw Error(
					    "ShapeVerifier: a split on no ObjectShape feature");
				out.threshold = sp.c;
				out.link = uint32_t(m_columns[std::size_t(sp.varIdx)]) << 24;
				stack.emplace_back(n.right, int(at));
				stack.emplace_back(n.left, -1);
			}
			else
				out.link = kLeaf << 24 |
				           uint32_t(
				               n.classIdx >= 0 && n.classIdx < votes.cols &&
				               votes.at<int>(0, n.classIdx) == 1);
		}
	}
}

double ShapeVerifier::score(const ObjectShape::Features& f) const
{
	if (!m_forest) return 1;
	// OpenCV's missing value takes another path: leave it to OpenCV.
	if (m_nodes.empty()) return scoreByOpenCv(f);
	for (float v : f)
		if (v == cv::ml::TrainData::missingValue()) return scoreByOpenCv(f);
	const FlatNode* nodes = m_nodes.data();
	// Eight trees at a time, a level of each in turn: their nodes' loads
	// overlap instead of waiting one for the other.
	constexpr std::size_t kLanes = 8;
	int object = 0;
	const std::size_t nTrees = m_roots.size();
	for (std::size_t t = 0; t < nTrees; t += kLanes)
	{
		const std::size_t lanes = std::min(kLanes, nTrees - t);
		uint32_t at[kLanes];
		for (std::size_t l = 0; l < lanes; l++) at[l] = m_roots[t + l];
		for (bool moved = true; moved;)
		{
			moved = false;
			for (std::size_t l = 0; l < lanes; l++)
			{
				const FlatNode n = nodes[at[l]];
				const uint32_t var = n.link >> 24;
				if (var == kLeaf) continue;
				moved = true;
				at[l] = f[var] <= n.threshold ? at[l] + 1 : n.link & kIndexMask;
			}
		}
		for (std::size_t l = 0; l < lanes; l++)
			object += int(nodes[at[l]].link & 1);
	}
	return nTrees == 0 ? 0 : double(object) / double(nTrees);
}

double ShapeVerifier::scoreByOpenCv(const ObjectShape::Features& f) const
{
	if (!m_forest) return 1;
	cv::Mat sample(1, featureCount(), CV_32F);
	for (int i = 0; i < featureCount(); i++)
		sample.at<float>(0, i) = f[std::size_t(m_columns[std::size_t(i)])];
	cv::Mat votes;
	m_forest->getVotes(sample, votes, 0);
	// Row 0: the class responses; row 1: this sample's votes per class.
	double object = 0, all = 0;
	for (int k = 0; k < votes.cols; k++)
	{
		all += votes.at<int>(1, k);
		if (votes.at<int>(0, k) == 1) object += votes.at<int>(1, k);
	}
	return all > 0 ? object / all : 0;
}

}  // namespace semnav
