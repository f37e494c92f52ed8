/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/config/CConfigFileBase.h>
#include <semnav/common/Error.h>
#include <semnav/common/OptionTable.h>
#include <semnav/training/GroundTruthObject.h>
#include <semnav/training/SampleGenerator.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <random>

namespace semnav
{
namespace
{

using O = SampleGenerator::TOptions;
const OptionTable<O>& optionTable()
{
	static const auto t =
	    OptionTable<O>()
	        .integer(
	            "positives", &O::positives, 1, 1000000,
	            "Positive samples per class.")
	        .integer(
	            "min_object_pixels", &O::minObjectPixels, 1, 1000000,
	            "Smallest instance cropped (detection-image pixels).")
	        .real(
	            "margin", &O::margin, 0.0, 2.0,
	            "Window side = (1 + margin) x the instance box's larger "
	            "side.")
	        .angle(
	            "max_x_angle_deg", &O::maxAngleX, 0, 80,
	            "Random rotations of the perspective warp (+-): x.")
	        .angle(
	            "max_y_angle_deg", &O::maxAngleY, 0, 80,
	            "Random rotations of the perspective warp (+-): y.")
	        .angle(
	            "max_z_angle_deg", &O::maxAngleZ, 0, 180,
	            "Random rotations of the perspective warp (+-): z.")
	        .real(
	            "max_intensity_dev", &O::maxIntensityDev, 0, 255,
	            "Random intensity shift (+-).")
	        .real(
	            "jitter", &O::jitter, 0, 0.5,
	            "Window centre / size jitter (fraction of the side).")
	        .real(
	            "background_scale", &O::backgroundScale, 1.0, 10.0,
	            "Background windows scaled by [1/s, s].")
	        .real(
	            "own_background_fraction", &O::ownBackgroundFraction, 0.0, 1.0,
	            "Share of positives keeping their real surroundings (0: the "
	            "paper's random backgrounds).")
	        .flag(
	            "range_negatives", &O::rangeNegatives,
	            "Negatives only from the windows the detector's range gate "
	            "lets through.");
	return t;
}

/** Seeded generator with platform-independent mappings. */
class Rng
{
public:
	explicit Rng(uint64_t seed) : m_g(seed) {}
	double uniform() { return double(m_g() >> 11) * 0x1.0p-53; }
	double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
	std::size_t below(std::size_t n)
	{
		return static_cast<std::size_t>(
		    (static_cast<unsigned __int128>(m_g()) * n) >> 64);
	}

private:
	std::mt19937_64 m_g;
};
/** A sweep's detection passes (one over the whole image if it has none). */
std::vector<DetectionPass> passesOf(const TrainingSweep& s, cv::Size window)
{
	if (!s.passes.empty()) return s.passes;
	DetectionPass whole;
	whole.rowEnd = s.image.rows;
	whole.minSide = std::max(window.width, window.height);
	return std::vector<DetectionPass>{whole};
}

/** A random square window of a random sweep of about `side` pixels, clear
 * of the class's boxes (`exclude`, per sweep; the 50th try is taken
 * anyway). */
cv::Mat randomBackground(
    const std::vector<TrainingSweep>& sweeps,
    const std::vector<std::vector<cv::Rect>>& exclude, double side, Rng& rng)
{
	cv::Mat background;
	for (int attempt = 0; attempt < 50 && background.empty(); attempt++)
	{
		const std::size_t b = rng.below(sweeps.size());
		const cv::Mat& img = sweeps[b].image;
		const int bs = std::clamp(
		    static_cast<int>(std::lround(side)), 3,
		    std::min(img.cols, img.rows));
		const cv::Rect r(
		    static_cast<int>(rng.below(std::size_t(img.cols - bs + 1))),
		    static_cast<int>(rng.below(std::size_t(img.rows - bs + 1))), bs,
		    bs);
		bool clear = true;
		for (const auto& e : exclude[b])
			if ((r & e).area() > 0) clear = false;
		if (clear || attempt == 49) background = img(r);
	}
	return background;
}
}  // namespace

const std::vector<std::string>& SampleGenerator::TOptions::knownKeys()
{
	static const std::vector<std::string> keys = optionTable().keys();
	return keys;
}

SEMNAV_OPTIONS_FROM_TABLE(SampleGenerator::TOptions, optionTable())

SampleGenerator::SampleGenerator() = default;
SampleGenerator::SampleGenerator(const TOptions& options) : m_options(options)
{
}

cv::Mat SampleGenerator::makePositive(
    const cv::Mat& image, const cv::Mat& objectMask, const cv::Rect& box,
    const cv::Vec3d& angles, double intensity, const cv::Mat& background,
    cv::Size window, double upscale, double shiftX, double shiftY,
    double sizeFactor) const
{
	// Window side around the instance and a patch twice as large, so that
	// the warp has material to rotate in.
	const double side = std::max(
	    3.0, std::max(box.width, box.height) * (1.0 + m_options.margin) *
	             sizeFactor);
	const cv::Point2d centre(
	    box.x + box.width * 0.5 + shiftX * side,
	    box.y + box.height * 0.5 + shiftY * side);
	const int P = static_cast<int>(std::ceil(2.0 * side)) | 1;
	const cv::Point origin(
	    static_cast<int>(std::lround(centre.x - P / 2.0)),
	    static_cast<int>(std::lround(centre.y - P / 2.0)));
	const cv::Rect patchRect(origin, cv::Size(P, P));
	const cv::Rect inside = patchRect & cv::Rect(0, 0, image.cols, image.rows);
	cv::Mat patch(P, P, CV_8UC1, cv::Scalar(0));
	cv::Mat alpha(P, P, CV_32FC1, cv::Scalar(0));
	if (inside.area() > 0)
	{
		const cv::Rect dst(inside.tl() - origin, inside.size());
		image(inside).copyTo(patch(dst));
		objectMask(inside).convertTo(alpha(dst), CV_32F, 1.0 / 255.0);
	}
	// Intensity change of the object (pixels without a normal stay 0).
	for (int r = 0; r < P; r++)
	{
		auto* p = patch.ptr<uint8_t>(r);
		const auto* a = alpha.ptr<float>(r);
		for (int c = 0; c < P; c++)
			if (a[c] > 0 && p[c] > 0)
				p[c] = cv::saturate_cast<uint8_t>(p[c] + intensity);
	}
	// Perspective warp: the patch plane rotated about x, y and z through its
	// centre and seen by a pinhole camera at distance f.
	const double cx = P / 2.0, cy = P / 2.0, f = 2.0 * P;
	const cv::Matx33d Rx(
	    1, 0, 0, 0, std::cos(angles[0]), -std::sin(angles[0]), 0,
	    std::sin(angles[0]), std::cos(angles[0]));
	const cv::Matx33d Ry(
	    std::cos(angles[1]), 0, std::sin(angles[1]), 0, 1, 0,
	    -std::sin(angles[1]), 0, std::cos(angles[1]));
	const cv::Matx33d Rz(
	    std::cos(angles[2]), -std::sin(angles[2]), 0, std::sin(angles[2]),
	    std::cos(angles[2]), 0, 0, 0, 1);
	const cv::Matx33d R = Rz * Ry * Rx;
	cv::Point2f src[4], dst[4];
	const double corner[4][2] = {
	    {0, 0}, {double(P), 0}, {double(P), double(P)}, {0, double(P)}};
	for (int i = 0; i < 4; i++)
	{
		const cv::Vec3d q =
		    R * cv::Vec3d(corner[i][0] - cx, corner[i][1] - cy, 0);
		src[i] = cv::Point2f(float(corner[i][0]), float(corner[i][1]));
		dst[i] = cv::Point2f(
		    float(cx + f * q[0] / (f + q[2])),
		    float(cy + f * q[1] / (f + q[2])));
	}
	const cv::Mat H = cv::getPerspectiveTransform(src, dst);
	cv::Mat warped, warpedAlpha;
	cv::warpPerspective(
	    patch, warped, H, patch.size(), cv::INTER_LINEAR, cv::BORDER_CONSTANT,
	    cv::Scalar(0));
	cv::Mat composite;
	if (background.empty())
		composite = warped;  // own surroundings
	else
	{
		cv::warpPerspective(
		    alpha, warpedAlpha, H, alpha.size(), cv::INTER_LINEAR,
		    cv::BORDER_CONSTANT, cv::Scalar(0));
		cv::Mat bg;
		cv::resize(background, bg, patch.size(), 0, 0, cv::INTER_LINEAR);
		composite.create(patch.size(), CV_8UC1);
		for (int r = 0; r < P; r++)
		{
			const auto* w = warped.ptr<uint8_t>(r);
			const auto* a = warpedAlpha.ptr<float>(r);
			const auto* b = bg.ptr<uint8_t>(r);
			auto* o = composite.ptr<uint8_t>(r);
			for (int c = 0; c < P; c++)
			{
				const float al = std::clamp(a[c], 0.0f, 1.0f);
				o[c] = cv::saturate_cast<uint8_t>(al * w[c] + (1 - al) * b[c]);
			}
		}
	}
	// The window around the object, scaled as the detector scales it:
	// by `upscale`, then down the pyramid to the window size.
	cv::Mat win;
	const int s = std::max(2, static_cast<int>(std::lround(side)));
	cv::getRectSubPix(
	    composite, cv::Size(s, s),
	    cv::Point2f(
	        float(cx + (centre.x - origin.x - cx)),
	        float(cy + (centre.y - origin.y - cy))),
	    win);
	if (upscale != 1.0)
	{
		const int us = std::max(2, static_cast<int>(std::lround(s * upscale)));
		cv::resize(win, win, cv::Size(us, us), 0, 0, cv::INTER_LINEAR);
	}
	cv::Mat out;
	cv::resize(win, out, window, 0, 0, cv::INTER_LINEAR);
	return out;
}

SampleGenerator::Result SampleGenerator::generate(
    const std::vector<TrainingSweep>& sweeps, Label label, cv::Size window,
    uint64_t seed) const
{
	struct View
	{
		std::size_t sweep;
		GroundTruthObject object;
	};
	Result res;
	std::vector<View> views;
	std::vector<std::vector<cv::Rect>> exclude(sweeps.size());
	for (std::size_t i = 0; i < sweeps.size(); i++)
	{
		const auto& s = sweeps[i];
		if (s.image.type() != CV_8UC1 || s.groundTruth.type() != CV_16UC1 ||
		    s.image.size() != s.groundTruth.size())
			throw Error(
			    "training sweep " + std::to_string(i) +
			    ": expected an 8-bit image and a 16-bit label image of the "
			    "same size");
		const auto objs =
		    GroundTruthObject::fromLabelImage(s.groundTruth, {label});
		for (const auto& o : objs)
		{
			exclude[i].push_back(o.box);
			if (o.pixels >= m_options.minObjectPixels) views.push_back({i, o});
		}
		if (objs.empty()) res.sweepsWithoutObject++;
	}
	if (views.empty())
		throw Error(
		    "no sweep shows a " + labelName(label) + " with at least " +
		    std::to_string(m_options.minObjectPixels) + " pixels");
	res.views = views.size();

	Rng rng(seed);
	// Instances in a seeded order, then in turn.
	for (std::size_t i = views.size(); i > 1; i--)
		std::swap(views[i - 1], views[rng.below(i)]);
	const double logBs = std::log(m_options.backgroundScale);
	for (int k = 0; k < m_options.positives; k++)
	{
		const View& v = views[std::size_t(k) % views.size()];
		const TrainingSweep& s = sweeps[v.sweep];
		const cv::Vec3d angles(
		    rng.uniform(-m_options.maxAngleX, m_options.maxAngleX),
		    rng.uniform(-m_options.maxAngleY, m_options.maxAngleY),
		    rng.uniform(-m_options.maxAngleZ, m_options.maxAngleZ));
		const double intensity =
		    rng.uniform(-m_options.maxIntensityDev, m_options.maxIntensityDev);
		const double j = m_options.jitter;
		const double shiftX = rng.uniform(-j, j), shiftY = rng.uniform(-j, j);
		const double sizeFactor = 1.0 + rng.uniform(-j, j);
		const bool own = rng.uniform() < m_options.ownBackgroundFraction;
		cv::Mat background;
		if (!own)
			background = randomBackground(
			    sweeps, exclude,
			    std::max(v.object.box.width, v.object.box.height) * 2.0 *
			        (1.0 + m_options.margin) *
			        std::exp(rng.uniform(-logBs, logBs)),
			    rng);
		// Scaled by the pass that searches objects of this size.
		const double side = std::max(v.object.box.width, v.object.box.height) *
		                    (1.0 + m_options.margin) * sizeFactor;
		const double upscale =
		    DetectionPass::forSide(passesOf(s, window), side).upscale;
		res.positives.push_back(makePositive(
		    s.image, v.object.mask(s.groundTruth), v.object.box, angles,
		    intensity, background, window, upscale, shiftX, shiftY,
		    sizeFactor));
	}

	res.negatives = negativeImages(sweeps, exclude, window);
	return res;
}

std::vector<NegativeImage> SampleGenerator::negativeImages(
    const std::vector<TrainingSweep>& sweeps,
    const std::vector<std::vector<cv::Rect>>& exclude, cv::Size window) const
{
	std::vector<NegativeImage> out;
	// Negatives: the sweeps' passes as the detector sees them.
	const double win = std::max(window.width, window.height);
	for (std::size_t i = 0; i < sweeps.size(); i++)
		for (const DetectionPass& p : passesOf(sweeps[i], window))
		{
			if (p.rowEnd <= p.rowBegin) continue;
			NegativeImage n;
			n.image = p.apply(sweeps[i].image);
			for (const auto& e : exclude[i]) n.exclude.push_back(p.toPass(e));
			n.minScale = std::max(1.0, p.minSide * p.upscale / win);
			n.maxScale = p.maxSide > 0 ? p.maxSide * p.upscale / win : 0.0;
			if (m_options.rangeNegatives && !sweeps[i].range.empty())
			{
				const cv::Mat& r = sweeps[i].range;
				cv::resize(
				    r.rowRange(
				        std::max(0, p.rowBegin), std::min(r.rows, p.rowEnd)),
				    n.range, n.image.size(), 0, 0, cv::INTER_NEAREST);
				n.gate = sweeps[i].gate;
				n.gate.perSide *= p.upscale;
			}
			out.push_back(std::move(n));
		}
	return out;
}

}  // namespace semnav
