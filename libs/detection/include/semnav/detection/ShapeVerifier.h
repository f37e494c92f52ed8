/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <semnav/detection/ObjectShape.h>

#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <opencv2/ml.hpp>
#include <string>
#include <vector>

namespace semnav
{
/** Tells whether a detected object has the 3D shape of its class: a random
 * forest (OpenCV's cv::ml::RTrees) over ObjectShape descriptors, trained on
 * the cascade's candidates in simulated sweeps (objects of the class
 * against furniture the cascade took for one). The score is the fraction of
 * trees that vote "object", from the forest's trees copied into flat arrays
 * (the same votes as cv::ml::RTrees::getVotes, without its allocations). */
class ShapeVerifier
{
public:
	struct TrainParams
	{
		int trees = 100;
		int maxDepth = 10;
		int minSampleCount = 10;
		/** Seeds OpenCV's random generator: same samples, same forest. */
		uint64_t seed = 1;
	};

	ShapeVerifier() = default;
	/** Trains on `samples` (CV_32F, one ObjectShape::Features per row, or
	 * the columns ObjectShape::columnsOf gives: without the grids or the
	 * steps) with
	 * `isObject` (CV_32S, 1 object / 0 not). Throws Error without samples
	 * of both kinds. */
	static ShapeVerifier train(
	    const cv::Mat& samples, const cv::Mat& isObject,
	    const TrainParams& params);
	/** Loads a forest saved by save(). Throws IoError naming `path` if it
	 * is missing, corrupt or not a forest over ObjectShape features. */
	static ShapeVerifier load(const std::string& path);
	/** Writes the forest (OpenCV XML, gzip-compressed when `path` ends in
	 * .gz; temp + rename). Throws IoError. */
	void save(const std::string& path) const;

	bool empty() const { return !m_forest; }
	/** How many ObjectShape features the forest was trained on
	 * (ObjectShape::columnsOf tells which; 0 when empty). */
	int featureCount() const;
	/** Whether the forest reads ObjectShape's steps. */
	bool readsSteps() const;
	/** Fraction of trees voting "object", in [0, 1]. */
	double score(const ObjectShape::Features& f) const;
	/** The same through cv::ml::RTrees::getVotes (slower; for checks). */
	double scoreByOpenCv(const ObjectShape::Features& f) const;

private:
	/** A tree node, the trees in preorder (a split's left child follows
	 * it): a split goes left if feature `link >> 24` is <= `threshold`,
	 * else to node `link & kIndexMask`; a leaf (`link >> 24` = kLeaf)
	 * votes `link & 1` for "object". 8 bytes: the trees of a forest stay
	 * in cache as far as they can. */
	struct FlatNode
	{
		float threshold = 0;
		uint32_t link = 0;
	};
	static constexpr uint32_t kLeaf = 0xff, kIndexMask = 0xffffff;
	/** Copies the forest's trees into m_roots / m_nodes (left empty when
	 * they do not fit FlatNode: score() then asks OpenCV). */
	void flatten();

	cv::Ptr<cv::ml::RTrees> m_forest;
	std::vector<uint32_t> m_roots;
	std::vector<FlatNode> m_nodes;
	/** The descriptor column of each of the forest's features. */
	std::vector<int> m_columns;
};

}  // namespace semnav
