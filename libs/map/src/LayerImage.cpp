/* semnav: semantic navigation from tilting-laser sweeps */
#include "LayerImage.h"

#include <semnav/common/Error.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "QuietStderr.h"

namespace semnav
{
namespace
{
std::string sizeText(long long cols, long long rows)
{
	return std::to_string(cols) + "x" + std::to_string(rows);
}

[[noreturn]] void wrongSize(
    const std::string& path, long long cols, long long rows, int wantCols,
    int wantRows)
{
	throw IoError(
	    "map image " + path + " is " + sizeText(cols, rows) +
	    ", map.yaml says " + sizeText(wantCols, wantRows));
}

/** PFM ("Pf", one channel): header "Pf W H SCALE" then W*H floats, bottom
 * row first, little-endian when SCALE < 0. */
cv::Mat decodePfm(
    const std::string& bytes, const std::string& path, int cols, int rows)
{
	const auto bad = [&](const std::string& what) -> IoError
	{ return IoError("corrupt PFM " + path + ": " + what); };
	std::size_t pos = 0;
	const auto token = [&]
	{
		while (pos < bytes.size() && std::isspace(uint8_t(bytes[pos]))) pos++;
		const std::size_t b = pos;
		while (pos < bytes.size() && pos - b < 32 &&
		       !std::isspace(uint8_t(bytes[pos])))
			pos++;
		return bytes.substr(b, pos - b);
	};
	if (token() != "Pf") throw bad("no single-channel PFM signature (\"Pf\")");
	long long w = -1, h = -1;
	double scale = 0;
	{
		const std::string tw = token(), th = token(), ts = token();
		std::istringstream is(tw + " " + th + " " + ts);
		if (!(is >> w >> h >> scale) || w < 0 || h < 0 ||
		    !std::isfinite(scale) || scale == 0)
			throw bad("bad header (expected width, height, scale)");
	}
	if (pos >= bytes.size() || !std::isspace(uint8_t(bytes[pos])))
		throw bad("bad header end");
	pos++;
	if (w != cols || h != rows) wrongSize(path, w, h, cols, rows);
	const std::size_t need = std::size_t(w) * std::size_t(h) * 4;
	if (bytes.size() - pos != need)
		throw bad(
		    std::to_string(bytes.size() - pos) + " bytes of pixels, " +
		    sizeText(w, h) + " needs " + std::to_string(need));
	const uint16_t one = 1;
	uint8_t first = 0;
	std::memcpy(&first, &one, 1);
	const bool swap = (scale < 0) != (first == 1);
	cv::Mat img(rows, cols, CV_32FC1);
	for (int r = 0; r < rows; r++)
	{
		uint8_t* dst = img.ptr<uint8_t>(rows - 1 - r);
		std::memcpy(
		    dst, bytes.data() + pos + std::size_t(r) * cols * 4,
		    std::size_t(cols) * 4);
		if (swap)
			for (int c = 0; c < cols; c++)
				std::reverse(dst + 4 * c, dst + 4 * c + 4);
	}
	return img;
}

uint32_t bigEndian32(const std::string& b, std::size_t at)
{
	return uint32_t(uint8_t(b[at])) << 24 | uint32_t(uint8_t(b[at + 1])) << 16 |
	       uint32_t(uint8_t(b[at + 2])) << 8 | uint32_t(uint8_t(b[at + 3]));
}

/** A grey PNG: the signature and IHDR checked first, then decoded with
 * libpng's and OpenCV's messages silenced. */
cv::Mat decodePng(
    const std::string& bytes, const std::string& path, int type, int cols,
    int rows)
{
	static const char kSignature[] = "\x89PNG\r\n\x1a\n";
	if (bytes.size() < 33 || bytes.compare(0, 8, kSignature, 8) != 0 ||
	    bytes.compare(12, 4, "IHDR") != 0)
		throw IoError("corrupt PNG " + path + ": no PNG signature and header");
	const uint32_t w = bigEndian32(bytes, 16), h = bigEndian32(bytes, 20);
	if (w != uint32_t(cols) || h != uint32_t(rows))
		wrongSize(path, w, h, cols, rows);
	const int depth = uint8_t(bytes[24]), colour = uint8_t(bytes[25]);
	const int wantDepth = type == CV_16UC1 ? 16 : 8;
	if (colour != 0 || depth != wantDepth)
		throw IoError(
		    "map image " + path + " has the wrong pixel type (want " +
		    std::to_string(wantDepth) + "-bit grey)");
	cv::Mat img;
	{
		const QuietStderr quiet;
		try
		{
			img = cv::imdecode(
			    cv::Mat(
			        1, static_cast<int>(bytes.size()), CV_8UC1,
			        const_cast<char*>(bytes.data())),
			    cv::IMREAD_UNCHANGED);
		}
		catch (const cv::Exception&)
		{
		}
	}
	if (img.empty()) throw IoError("corrupt PNG " + path + ": cannot decode");
	if (img.type() != type || img.cols != cols || img.rows != rows)
		throw IoError("map image " + path + " has the wrong pixel type");
	return img;
}
}  // namespace

cv::Mat decodeLayerImage(
    const std::string& bytes, const std::string& path, int type, int cols,
    int rows)
{
	if (type == CV_32FC1) return decodePfm(bytes, path, cols, rows);
	return decodePng(bytes, path, type, cols, rows);
}

void checkLayerValues(
    const cv::Mat& img, const std::string& path, const LayerRange& range)
{
	for (int r = 0; r < img.rows; r++)
		for (int c = 0; c < img.cols; c++)
		{
			const float v = img.at<float>(r, c);
			if (std::isnan(v) ? range.nanMeansNoData
			                  : v >= range.lowest && v <= range.highest)
				continue;
			std::ostringstream os;
			os << "map layer " << path << ": pixel (" << c << ", " << r
			   << ") is " << v << "; values must be "
			   << (range.nanMeansNoData ? "NaN (no data) or " : "") << "finite";
			if (range.lowest > -std::numeric_limits<float>::max())
				os << " and >= " << range.lowest;
			if (range.highest < std::numeric_limits<float>::max())
				os << " and <= " << range.highest;
			throw IoError(os.str());
		}
}

}  // namespace semnav
