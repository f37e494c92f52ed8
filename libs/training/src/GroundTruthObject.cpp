/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/Error.h>
#include <semnav/training/GroundTruthObject.h>

#include <algorithm>
#include <map>
#include <opencv2/core.hpp>

namespace semnav
{
namespace
{
/** The ground-truth pixel value of an instance (label | instance << 8). */
uint16_t codeOf(const GroundTruthObject& o)
{
	return static_cast<uint16_t>(static_cast<int>(o.label) | (o.instance << 8));
}
}  // namespace

std::vector<GroundTruthObject> GroundTruthObject::fromLabelImage(
    const cv::Mat& gt, const std::vector<Label>& labels)
{
	if (gt.type() != CV_16UC1)
		throw Error(
		    "ground-truth image must be CV_16U (label | instance << 8)");
	bool wanted[256] = {};
	for (Label l : labels) wanted[static_cast<int>(l)] = true;
	std::map<std::pair<int, int>, GroundTruthObject> found;
	for (int r = 0; r < gt.rows; r++)
	{
		const auto* p = gt.ptr<uint16_t>(r);
		for (int c = 0; c < gt.cols; c++)
		{
			const int label = p[c] & 0xff, inst = p[c] >> 8;
			if (!wanted[label] || inst == 0) continue;
			auto& o = found[{label, inst}];
			if (o.pixels == 0)
			{
				o.label = labelFromId(static_cast<unsigned>(label));
				o.instance = inst;
				o.box = cv::Rect(c, r, 1, 1);
			}
			else
				o.box |= cv::Rect(c, r, 1, 1);
			o.pixels++;
		}
	}
	std::vector<GroundTruthObject> out;
	for (auto& kv : found) out.push_back(kv.second);
	return out;
}

cv::Mat GroundTruthObject::mask(const cv::Mat& gt) const
{
	cv::Mat m;
	cv::compare(gt, cv::Scalar(codeOf(*this)), m, cv::CMP_EQ);
	return m;
}

double GroundTruthObject::shareOf(
    const cv::Mat& gt, const std::vector<cv::Point>& pixels) const
{
	if (pixels.empty()) return 0;
	const uint16_t code = codeOf(*this);
	std::size_t on = 0;
	for (const auto& p : pixels) on += gt.at<uint16_t>(p) == code;
	return double(on) / double(pixels.size());
}

}  // namespace semnav
