/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/cascade/CascadeError.h>
#include <semnav/cascade/HaarFeature.h>

#include <algorithm>
#include <cctype>

namespace semnav
{
const std::string& haarModeName(HaarMode m)
{
	static const std::string names[] = {"BASIC", "CORE", "ALL"};
	return names[static_cast<int>(m)];
}

HaarMode haarModeFromName(const std::string& name)
{
	std::string up = name;
	std::transform(
	    up.begin(), up.end(), up.begin(),
	    [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
	for (auto m : {HaarMode::Basic, HaarMode::Core, HaarMode::All})
		if (haarModeName(m) == up) return m;
	throw CascadeError(
	    "unknown Haar feature mode '" + name + "' (BASIC, CORE or ALL)");
}

float HaarFeature::evaluate(const IntegralImages& ii, cv::Point o) const
{
	const auto rs = [&](const cv::Rect& r)
	{
		const cv::Rect s(r.x + o.x, r.y + o.y, r.width, r.height);
		return static_cast<int>(tilted ? ii.tiltedRectSum(s) : ii.rectSum(s));
	};
	// OpenCV: float ret = w0 * sum0 + w1 * sum1; if (w2) ret += w2 * sum2.
	float ret = rects[0].weight * static_cast<float>(rs(rects[0].rect)) +
	            rects[1].weight * static_cast<float>(rs(rects[1].rect));
	if (count > 2 && rects[2].weight != 0.0f)
		ret += rects[2].weight * static_cast<float>(rs(rects[2].rect));
	return ret;
}

double HaarFeature::bruteForce(const cv::Mat& window) const
{
	double v = 0;
	for (int i = 0; i < count; i++)
	{
		const cv::Rect& r = rects[i].rect;
		double s = 0;
		for (int y = 0; y < window.rows; y++)
			for (int x = 0; x < window.cols; x++)
			{
				const bool in = tilted ? IntegralImages::inTiltedRect(r, x, y)
				                       : r.contains({x, y});
				if (in) s += window.at<uint8_t>(y, x);
			}
		v += rects[i].weight * s;
	}
	return v;
}

bool HaarFeature::fitsIn(cv::Size win) const
{
	for (int i = 0; i < count; i++)
	{
		const cv::Rect& r = rects[i].rect;
		if (r.width <= 0 || r.height <= 0) return false;
		if (!tilted)
		{
			if (r.x < 0 || r.y < 0 || r.x + r.width > win.width ||
			    r.y + r.height > win.height)
				return false;
		}
		else
		{
			// Corners (x, y), (x - h, y + h), (x + w, y + w),
			// (x + w - h, y + w + h) of the tilted integral image.
			if (r.y < 0 || r.x - r.height < 0 || r.x + r.width > win.width ||
			    r.y + r.width + r.height > win.height)
				return false;
		}
	}
	return count >= 2;
}

bool HaarFeature::operator==(const HaarFeature& o) const
{
	if (count != o.count || tilted != o.tilted) return false;
	for (int i = 0; i < count; i++)
		if (rects[i].rect != o.rects[i].rect ||
		    rects[i].weight != o.rects[i].weight)
			return false;
	return true;
}

namespace
{
HaarFeature make(
    bool tilted, cv::Rect r0, float w0, cv::Rect r1, float w1, cv::Rect r2 = {},
    float w2 = 0)
{
	HaarFeature f;
	f.tilted = tilted;
	f.rects[0] = {r0, w0};
	f.rects[1] = {r1, w1};
	f.rects[2] = {r2, w2};
	f.count = w2 != 0 ? 3 : 2;
	return f;
}
}  // namespace

std::vector<HaarFeature> generateHaarFeatures(cv::Size win, HaarMode mode)
{
	// Same loops, conditions and order as OpenCV's
	// CvHaarEvaluator::generateFeatures (apps/traincascade/haarfeatures.cpp).
	std::vector<HaarFeature> f;
	const int W = win.width, H = win.height;
	for (int x = 0; x < W; x++)
		for (int y = 0; y < H; y++)
			for (int dx = 1; dx <= W; dx++)
				for (int dy = 1; dy <= H; dy++)
				{
					using R = cv::Rect;
					if (x + dx * 2 <= W && y + dy <= H)  // haar_x2
						f.push_back(make(
						    false, R(x, y, dx * 2, dy), -1,
						    R(x + dx, y, dx, dy), +2));
					if (x + dx <= W && y + dy * 2 <= H)  // haar_y2
						f.push_back(make(
						    false, R(x, y, dx, dy * 2), -1,
						    R(x, y + dy, dx, dy), +2));
					if (x + dx * 3 <= W && y + dy <= H)  // haar_x3
						f.push_back(make(
						    false, R(x, y, dx * 3, dy), -1,
						    R(x + dx, y, dx, dy), +3));
					if (x + dx <= W && y + dy * 3 <= H)  // haar_y3
						f.push_back(make(
						    false, R(x, y, dx, dy * 3), -1,
						    R(x, y + dy, dx, dy), +3));
					if (mode != HaarMode::Basic)
					{
						if (x + dx * 4 <= W && y + dy <= H)  // haar_x4
							f.push_back(make(
							    false, R(x, y, dx * 4, dy), -1,
							    R(x + dx, y, dx * 2, dy), +2));
						if (x + dx <= W && y + dy * 4 <= H)  // haar_y4
							f.push_back(make(
							    false, R(x, y, dx, dy * 4), -1,
							    R(x, y + dy, dx, dy * 2), +2));
					}
					if (x + dx * 2 <= W && y + dy * 2 <= H)  // x2_y2
						f.push_back(make(
						    false, R(x, y, dx * 2, dy * 2), -1, R(x, y, dx, dy),
						    +2, R(x + dx, y + dy, dx, dy), +2));
					if (mode != HaarMode::Basic)
					{
						if (x + dx * 3 <= W && y + dy * 3 <= H)  // centre
							f.push_back(make(
							    false, R(x, y, dx * 3, dy * 3), -1,
							    R(x + dx, y + dy, dx, dy), +9));
					}
					if (mode == HaarMode::All)
					{
						// tilted haar_x2
						if (x + 2 * dx <= W && y + 2 * dx + dy <= H &&
						    x - dy >= 0)
							f.push_back(make(
							    true, R(x, y, dx * 2, dy), -1, R(x, y, dx, dy),
							    +2));
						// tilted haar_y2
						if (x + dx <= W && y + dx + 2 * dy <= H &&
						    x - 2 * dy >= 0)
							f.push_back(make(
							    true, R(x, y, dx, 2 * dy), -1, R(x, y, dx, dy),
							    +2));
						// tilted haar_x3
						if (x + 3 * dx <= W && y + 3 * dx + dy <= H &&
						    x - dy >= 0)
							f.push_back(make(
							    true, R(x, y, dx * 3, dy), -1,
							    R(x + dx, y + dx, dx, dy), +3));
						// tilted haar_y3
						if (x + dx <= W && y + dx + 3 * dy <= H &&
						    x - 3 * dy >= 0)
							f.push_back(make(
							    true, R(x, y, dx, 3 * dy), -1,
							    R(x - dy, y + dy, dx, dy), +3));
						// tilted haar_x4
						if (x + 4 * dx <= W && y + 4 * dx + dy <= H &&
						    x - dy >= 0)
							f.push_back(make(
							    true, R(x, y, dx * 4, dy), -1,
							    R(x + dx, y + dx, dx * 2, dy), +2));
						// tilted haar_y4
						if (x + dx <= W && y + dx + 4 * dy <= H &&
						    x - 4 * dy >= 0)
							f.push_back(make(
							    true, R(x, y, dx, 4 * dy), -1,
							    R(x - dy, y + dy, dx, 2 * dy), +2));
					}
				}
	return f;
}

}  // namespace semnav
