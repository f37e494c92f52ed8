/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/core/bits_math.h>
#include <semnav/common/Error.h>
#include <semnav/common/OptionTable.h>
#include <semnav/scan/ThreeDtkReader.h>
#include <semnav/scan/TiltGeometry.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace semnav
{
using mrpt::DEG2RAD;
using mrpt::RAD2DEG;

namespace
{
using O = ThreeDtkReader::TOptions;
const OptionTable<O>& optionTable()
{
	static const auto t =
	    OptionTable<O>()
	        .integer("cols", &O::cols, 1, 10000, "Beams per scan line.")
	        .angle(
	            "beam_step_deg", &O::beamStep, 0.01, 5, "Angle between beams.")
	        .real(
	            "no_return_range_m", &O::noReturnRange, 0.1, 1000,
	            "Range written for beams without a return.")
	        .real(
	            "min_range_m", &O::minRange, 0, 100,
	            "Closer returns are invalid.")
	        .real(
	            "max_range_m", &O::maxRange, 0.1, 1000,
	            "Farther returns are invalid.");
	return t;
}
}  // namespace

SEMNAV_OPTIONS_FROM_TABLE(ThreeDtkReader::TOptions, optionTable())

ThreeDtkReader::ThreeDtkReader() : ThreeDtkReader(TOptions()) {}

ThreeDtkReader::ThreeDtkReader(const TOptions& options) : m_options(options) {}

namespace
{
struct RawPoint
{
	double x, y, z;  // 3DTK frame, metres
};
}  // namespace

Sweep ThreeDtkReader::read(const std::string& path) const
{
	std::ifstream f(path);
	if (!f) throw IoError("cannot open 3DTK scan " + path);
	std::vector<RawPoint> pts;
	pts.reserve(81360);
	std::string line;
	std::size_t lineNo = 0;
	while (std::getline(f, line))
	{
		lineNo++;
		if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
		std::istringstream is(line);
		RawPoint p{};
		if (!(is >> p.x >> p.y >> p.z))
			throw IoError(
			    path + ":" + std::to_string(lineNo) +
			    ": expected 'x y z' in cm, got '" + line + "'");
		pts.push_back({p.x / 100, p.y / 100, p.z / 100});
	}
	const std::size_t cols = m_options.cols;
	if (pts.empty() || pts.size() % cols != 0)
		throw IoError(
		    path + ": " + std::to_string(pts.size()) +
		    " points is not a whole number of " + std::to_string(cols) +
		    "-beam scan lines");
	const std::size_t rows = pts.size() / cols;

	auto rangeOf = [](const RawPoint& p)
	{ return std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z); };
	auto isValid = [&](double r)
	{ return r >= m_options.minRange && r < m_options.noReturnRange; };

	// Tilt of each file row, from the beams that are well off the tilt axis.
	std::vector<double> theta(rows, std::nan(""));
	for (std::size_t r = 0; r < rows; r++)
	{
		std::vector<double> t;
		for (std::size_t c = 0; c < cols; c++)
		{
			const auto& p = pts[r * cols + c];
			const double rg = rangeOf(p);
			if (rg < m_options.minRange) continue;
			const double yz = std::hypot(p.y, p.z);
			if (yz < 0.3 * rg) continue;
			t.push_back(std::atan2(p.y, p.z));
		}
		if (t.empty()) continue;
		std::nth_element(t.begin(), t.begin() + t.size() / 2, t.end());
		theta[r] = t[t.size() / 2];
	}
	// Rows without usable beams: interpolate between known neighbours.
	for (std::size_t r = 0; r < rows; r++)
	{
		if (!std::isnan(theta[r])) continue;
		std::size_t a = r, b = r;
		while (a > 0 && std::isnan(theta[a])) a--;
		while (b + 1 < rows && std::isnan(theta[b])) b++;
		if (std::isnan(theta[a]) && std::isnan(theta[b]))
			throw IoError(path + ": no valid readings to find the tilt");
		if (std::isnan(theta[a]))
			theta[r] = theta[b];
		else if (std::isnan(theta[b]))
			theta[r] = theta[a];
		else
			theta[r] = theta[a] +
			           (theta[b] - theta[a]) * double(r - a) / double(b - a);
	}

	const bool ascending = theta.back() >= theta.front();
	Sweep sw(rows, cols);
	std::vector<double> phi(cols);
	for (std::size_t c = 0; c < cols; c++)
		phi[c] = -M_PI / 2 + c * m_options.beamStep;
	sw.setPhis(phi);
	for (std::size_t fr = 0; fr < rows; fr++)
	{
		const std::size_t r = ascending ? fr : rows - 1 - fr;
		sw.setRow(r, theta[fr], tiltedSensorPose({0, 0, 0}, theta[fr]));
		for (std::size_t c = 0; c < cols; c++)
		{
			const double rg = rangeOf(pts[fr * cols + c]);
			sw.setRange(r, c, static_cast<float>(rg), isValid(rg));
		}
	}
	sw.setMaxRange(static_cast<float>(m_options.maxRange));
	sw.setSensorLabel("3DTK");
	sw.quality().ascending = ascending;

	if (const std::string pose = posePath(path); std::filesystem::exists(pose))
	{
		const auto p = readPose(pose);
		sw.setOdometry(mrpt::poses::CPose2D(p.x(), p.y(), p.yaw()));
	}
	return sw;
}

std::string ThreeDtkReader::posePath(const std::string& scanPath)
{
	return std::filesystem::path(scanPath).replace_extension(".pose").string();
}

mrpt::poses::CPose3D ThreeDtkReader::readPose(const std::string& path)
{
	std::ifstream f(path);
	if (!f) throw IoError("cannot open 3DTK pose " + path);
	double x, y, z, rx, ry, rz;
	if (!(f >> x >> y >> z >> rx >> ry >> rz))
		throw IoError(path + ": expected 'x y z' (cm) and 3 angles (deg)");
	// Left-handed (x right, y up, z forward) -> x forward, y left, z up. A
	// positive rotation about 3DTK's up axis turns toward the right.
	return mrpt::poses::CPose3D(
	    z / 100, -x / 100, y / 100, DEG2RAD(-ry), DEG2RAD(-rx), DEG2RAD(rz));
}

}  // namespace semnav
