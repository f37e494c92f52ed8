/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/ClassRegistry.h>
#include <semnav/perception/PerceptionImages.h>

#include <algorithm>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace semnav::perception_images
{
cv::Mat toViewerLayout(const cv::Mat& m)
{
	cv::Mat out;
	if (m.empty()) return m.clone();
	cv::flip(m, out, -1);
	return out;
}

cv::Vec3b labelColour(Label l)
{
	const auto& registry = ClassRegistry::instance();
	const ClassInfo::Rgb c =
	    registry.info(registry.contains(l) ? l : Label::Unknown).labelColour;
	return cv::Vec3b(c.b, c.g, c.r);
}

cv::Mat normals(const cv::Mat& bgr)
{
	return toViewerLayout(bgr);
}

cv::Mat segments(const cv::Mat& areaIds)
{
	cv::Mat out(areaIds.rows, areaIds.cols, CV_8UC3, cv::Scalar::all(0));
	for (int r = 0; r < areaIds.rows; r++)
		for (int c = 0; c < areaIds.cols; c++)
		{
			const int id = areaIds.at<int>(r, c);
			if (id <= 0) continue;
			uint32_t h = static_cast<uint32_t>(id) * 2654435761u;
			h ^= h >> 15;
			h *= 2246822519u;
			h ^= h >> 13;
			out.at<cv::Vec3b>(r, c) = cv::Vec3b(
			    static_cast<uchar>(60 + (h & 0xFF) % 196),
			    static_cast<uchar>(60 + ((h >> 8) & 0xFF) % 196),
			    static_cast<uchar>(60 + ((h >> 16) & 0xFF) % 196));
		}
	return toViewerLayout(out);
}

cv::Mat labels(const cv::Mat& labelIds, const cv::Mat& validMask)
{
	cv::Mat img(labelIds.rows, labelIds.cols, CV_8UC3, cv::Scalar::all(0));
	for (int r = 0; r < labelIds.rows; r++)
		for (int c = 0; c < labelIds.cols; c++)
		{
			if (!validMask.empty() && !validMask.at<uint8_t>(r, c)) continue;
			img.at<cv::Vec3b>(r, c) =
			    labelColour(static_cast<Label>(labelIds.at<uint8_t>(r, c)));
		}
	img = toViewerLayout(img);
	// Legend: one swatch + name per label, in rows below the image.
	const int w = std::max(img.cols, 360), cellW = 120, cellH = 18;
	const int perRow = std::max(1, w / cellW);
	const std::size_t count = allLabels().size();
	const int legendRows = static_cast<int>((count + perRow - 1) / perRow);
	cv::Mat out(
	    img.rows + legendRows * cellH + 4, w, CV_8UC3, cv::Scalar::all(255));
	img.copyTo(out(cv::Rect(0, 0, img.cols, img.rows)));
	for (std::size_t i = 0; i < count; i++)
	{
		const int x = static_cast<int>(i % perRow) * cellW + 4;
		const int y = img.rows + 4 + static_cast<int>(i / perRow) * cellH;
		const cv::Vec3b col = labelColour(static_cast<Label>(i));
		cv::rectangle(
		    out, cv::Rect(x, y + 2, 12, 12), cv::Scalar(col[0], col[1], col[2]),
		    cv::FILLED);
		cv::putText(
		    out, labelName(static_cast<Label>(i)), cv::Point(x + 16, y + 13),
		    cv::FONT_HERSHEY_SIMPLEX, 0.4, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
	}
	return out;
}

}  // namespace semnav::perception_images
