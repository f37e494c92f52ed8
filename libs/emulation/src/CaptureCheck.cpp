/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <semnav/common/Error.h>
#include <semnav/emulation/CaptureCheck.h>
#include <semnav/emulation/SceneLineCaster.h>
#include <semnav/scan/RawlogObjectReader.h>
#include <semnav/scan/TiltGeometry.h>

#include <algorithm>
#include <cmath>
#include <fstream>

namespace semnav
{
namespace
{
/** Every sweep of the rawlog at `path` (counting its objects and lines;
 * a read error ends it as truncated). */
std::vector<Sweep> readCapturedSweeps(
    const std::string& path, double nominalSpan, CaptureCheckResult& res)
{
	RawlogObjectReader in(path);
	SweepAssembler::TOptions ao;
	ao.nominalSpan = nominalSpan;
	SweepAssembler assembler(ao);
	assembler.setMinLoggingLevel(mrpt::system::LVL_ERROR);
	std::vector<Sweep> sweeps;
	auto drain = [&]
	{
		while (assembler.hasSweep()) sweeps.push_back(assembler.pop());
	};
	for (;;)
	{
		mrpt::serialization::CSerializable::Ptr obj;
		try
		{
			if (!in.next(obj)) break;
		}
		catch (const RawlogError& e)
		{
			res.truncated = true;
			res.truncation = e.what();
			break;
		}
		res.objects++;
		auto obs = std::dynamic_pointer_cast<mrpt::obs::CObservation>(obj);
		if (!obs) continue;
		if (IS_CLASS(*obs, mrpt::obs::CObservation2DRangeScan)) res.lines++;
		assembler.push(obs);
		drain();
	}
	assembler.finish();
	drain();
	if (res.lines == 0)
		throw RawlogError(
		    res.truncated ? res.truncation
		                  : "rawlog " + path + " holds no scan line (" +
		                        std::to_string(res.objects) + " objects)");
	return sweeps;
}

/** Range errors of the captured sweeps against the ray-cast truth. */
struct RangeErrors
{
	std::vector<double> absErr;
	/** Pixels within 3 sigma of the truth at the line's tilt, and of the
	 * truth anywhere within the tilt tolerance. */
	std::size_t in3 = 0, in3t = 0;
};

/** Compares line r of s with the truth cast from `robot`. */
void compareLine(
    const Sweep& s, std::size_t r, const SceneLineCaster& caster,
    const mrpt::math::TPose2D& robot, double sigma, double tiltTol,
    RangeErrors& err, CaptureCheckResult& res)
{
	const auto& sp = s.sensorPose(r);
	const mrpt::math::TPoint3D mount(sp.x(), sp.y(), sp.z());
	const double maxR = 1.5 * s.maxRange();
	const auto t0 = caster.cast(robot, sp, s.phis(), maxR);
	const auto tLo = caster.cast(
	    robot, tiltedSensorPose(mount, s.theta(r) - tiltTol), s.phis(), maxR);
	const auto tHi = caster.cast(
	    robot, tiltedSensorPose(mount, s.theta(r) + tiltTol), s.phis(), maxR);
	for (std::size_t c = 0; c < s.cols(); c++)
	{
		const bool truthValid = t0[c] > 0 && t0[c] <= s.maxRange();
		if (!s.valid(r, c))
		{
			// Near max range noise decides; count clear misses only.
			if (truthValid && t0[c] < s.maxRange() - 5 * sigma) res.missed++;
			continue;
		}
		if (t0[c] <= 0)
		{
			res.spurious++;
			continue;
		}
		const double m = s.range(r, c);
		const double e = std::abs(m - t0[c]);
		err.absErr.push_back(e);
		if (e <= 3 * sigma) err.in3++;
		double best = e;
		// Between the two bracketing tilts the truth is continuous unless an
		// edge lies between; take the closest of the three or the measured
		// value if it lies between them.
		for (double t : {tLo[c], tHi[c]})
			if (t > 0) best = std::min(best, std::abs(m - t));
		const double lo = std::min({t0[c], tLo[c], tHi[c]});
		const double hi = std::max({t0[c], tLo[c], tHi[c]});
		if (tLo[c] > 0 && tHi[c] > 0 && m >= lo && m <= hi) best = 0;
		if (best <= 3 * sigma) err.in3t++;
	}
}
}  // namespace

CaptureCheckResult checkCapture(
    const std::string& path, const SceneLineCaster& caster,
    const mrpt::math::TPose2D& robot, double sigma, double tiltTol,
    double nominalSpan)
{
	CaptureCheckResult res;
	const std::vector<Sweep> sweeps =
	    readCapturedSweeps(path, nominalSpan, res);
	RangeErrors err;
	for (const Sweep& s : sweeps)
	{
		CaptureCheckResult::SweepInfo info;
		info.rows = s.rows();
		info.cols = s.cols();
		const std::size_t pixels0 = err.absErr.size(), in3t0 = err.in3t;
		info.missingLines = s.quality().missingLines;
		info.thetaMin = s.rows() ? s.theta(0) : 0;
		info.thetaMax = s.rows() ? s.theta(s.rows() - 1) : 0;
		info.complete = s.quality().complete;
		res.sweeps.push_back(info);
		// Every sweep's pixels are compared; only whole ones count as sweeps.
		if (s.quality().complete)
			res.sweepsComplete++;
		else
			res.sweepsIncomplete++;
		for (std::size_t r = 0; r < s.rows(); r++)
		{
			bool any = false;
			for (std::size_t c = 0; c < s.cols() && !any; c++)
				any = s.valid(r, c);
			if (!any) continue;  // missing line
			compareLine(s, r, caster, robot, sigma, tiltTol, err, res);
		}
		auto& last = res.sweeps.back();
		last.pixels = err.absErr.size() - pixels0;
		last.within3SigmaTilt =
		    last.pixels ? static_cast<double>(err.in3t - in3t0) / last.pixels
		                : 0;
	}
	auto& absErr = err.absErr;
	res.pixels = absErr.size();
	if (!absErr.empty())
	{
		std::nth_element(
		    absErr.begin(), absErr.begin() + absErr.size() / 2, absErr.end());
		res.medianAbsError = absErr[absErr.size() / 2];
		res.within3Sigma = static_cast<double>(err.in3) / absErr.size();
		res.within3SigmaTilt = static_cast<double>(err.in3t) / absErr.size();
	}
	return res;
}

TiltCheckResult checkTilts(
    const std::string& rawlogPath, const std::string& truthLogPath)
{
	std::ifstream tf(truthLogPath);
	if (!tf) throw IoError("cannot read " + truthLogPath);
	std::vector<std::pair<double, double>> truth;
	double t, th;
	while (tf >> t >> th) truth.emplace_back(t, th);
	RawlogObjectReader in(rawlogPath);
	std::vector<double> errs, offsets;
	for (;;)
	{
		mrpt::serialization::CSerializable::Ptr obj;
		try
		{
			if (!in.next(obj)) break;
		}
		catch (const RawlogError&)
		{
			break;  // checkCapture() reported it
		}
		auto scan =
		    std::dynamic_pointer_cast<mrpt::obs::CObservation2DRangeScan>(obj);
		if (!scan || truth.empty()) continue;
		const double ts = mrpt::Clock::toDouble(scan->timestamp);
		auto it = std::lower_bound(
		    truth.begin(), truth.end(), std::make_pair(ts, -1e9));
		double best = 1e9, bestTheta = 0, bestDt = 0;
		for (auto j : {it, it == truth.begin() ? it : std::prev(it)})
			if (j != truth.end() && std::abs(j->first - ts) < best)
			{
				best = std::abs(j->first - ts);
				bestTheta = j->second;
				bestDt = ts - j->first;
			}
		if (best > 0.005) continue;
		errs.push_back(
		    std::abs(tiltOfSensorPose(scan->sensorPose) - bestTheta));
		offsets.push_back(bestDt);
	}
	TiltCheckResult r;
	r.matched = errs.size();
	if (errs.empty()) return r;
	auto quantile = [](std::vector<double> v, double q)
	{
		const std::size_t k =
		    std::min(v.size() - 1, static_cast<std::size_t>(q * v.size()));
		std::nth_element(v.begin(), v.begin() + k, v.end());
		return v[k];
	};
	r.medianAbsErrorDeg = mrpt::RAD2DEG(quantile(errs, 0.5));
	r.p95AbsErrorDeg = mrpt::RAD2DEG(quantile(errs, 0.95));
	r.medianTimeOffsetMs = 1000 * quantile(offsets, 0.5);
	return r;
}

}  // namespace semnav
