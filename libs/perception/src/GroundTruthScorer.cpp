/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/Error.h>
#include <semnav/perception/GroundTruthScorer.h>

#include <opencv2/imgcodecs.hpp>

namespace semnav
{
void GroundTruthScorer::add(
    const cv::Mat& predicted, const cv::Mat& groundTruth,
    const cv::Mat& validMask)
{
	if (predicted.size() != groundTruth.size() ||
	    predicted.size() != validMask.size())
		throw Error(
		    "ground truth " + std::to_string(groundTruth.rows) + "x" +
		    std::to_string(groundTruth.cols) + " does not match the sweep " +
		    std::to_string(predicted.rows) + "x" +
		    std::to_string(predicted.cols));
	if (predicted.type() != CV_8U || validMask.type() != CV_8U ||
	    (groundTruth.type() != CV_8U && groundTruth.type() != CV_16U))
		throw Error("GroundTruthScorer: unexpected image types");
	const bool wide = groundTruth.type() == CV_16U;
	const std::size_t count = allLabels().size();
	for (int r = 0; r < predicted.rows; r++)
	{
		const uint8_t* P = predicted.ptr<uint8_t>(r);
		const uint8_t* V = validMask.ptr<uint8_t>(r);
		for (int c = 0; c < predicted.cols; c++)
		{
			if (!V[c]) continue;
			const unsigned g = wide ? (groundTruth.ptr<uint16_t>(r)[c] & 0xFFu)
			                        : groundTruth.ptr<uint8_t>(r)[c];
			if (g >= count || P[c] >= count)
				throw Error(
				    "label id " + std::to_string(std::max<unsigned>(g, P[c])) +
				    " is not a semnav label");
			m_conf[g][P[c]]++;
			m_pixels++;
		}
	}
	m_sweeps++;
}

GroundTruthScorer::ClassScore GroundTruthScorer::score(Label l) const
{
	const auto i = static_cast<std::size_t>(l);
	ClassScore s;
	for (std::size_t k = 0; k < kMaxLabelCount; k++)
	{
		s.groundTruthPixels += m_conf[i][k];
		s.predictedPixels += m_conf[k][i];
	}
	s.truePositives = m_conf[i][i];
	s.falseNegatives = s.groundTruthPixels - s.truePositives;
	s.falsePositives = s.predictedPixels - s.truePositives;
	if (s.predictedPixels > 0)
		s.precision = double(s.truePositives) / double(s.predictedPixels);
	if (s.groundTruthPixels > 0)
		s.recall = double(s.truePositives) / double(s.groundTruthPixels);
	if (s.precision + s.recall > 0)
		s.f1 = 2 * s.precision * s.recall / (s.precision + s.recall);
	return s;
}

std::vector<Label> GroundTruthScorer::labelsSeen() const
{
	std::vector<Label> out;
	for (std::size_t i = 1; i < allLabels().size(); i++)
	{
		const auto s = score(static_cast<Label>(i));
		if (s.groundTruthPixels > 0 || s.predictedPixels > 0)
			out.push_back(static_cast<Label>(i));
	}
	return out;
}

std::size_t GroundTruthScorer::confusion(Label gt, Label pred) const
{
	return m_conf[static_cast<std::size_t>(gt)][static_cast<std::size_t>(pred)];
}

cv::Mat GroundTruthScorer::readLabelImage(const std::string& path)
{
	const cv::Mat img = cv::imread(path, cv::IMREAD_UNCHANGED);
	if (img.empty()) throw IoError("cannot read label image " + path);
	if (img.channels() != 1 || (img.depth() != CV_8U && img.depth() != CV_16U))
		throw IoError(
		    "label image " + path + " is not a 1-channel 8- or 16-bit PNG");
	cv::Mat out(img.rows, img.cols, CV_8U);
	const std::size_t count = allLabels().size();
	for (int r = 0; r < img.rows; r++)
		for (int c = 0; c < img.cols; c++)
		{
			const unsigned v = img.depth() == CV_16U
			                       ? (img.at<uint16_t>(r, c) & 0xFFu)
			                       : img.at<uint8_t>(r, c);
			if (v >= count)
				throw IoError(
				    "label image " + path + " holds label id " +
				    std::to_string(v) + ", not a semnav label");
			out.at<uint8_t>(r, c) = static_cast<uint8_t>(v);
		}
	return out;
}

}  // namespace semnav
