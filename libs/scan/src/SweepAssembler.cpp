/* semnav: semantic navigation from tilting-laser sweeps */
#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <semnav/common/OptionTable.h>
#include <semnav/scan/SweepAssembler.h>
#include <semnav/scan/TiltGeometry.h>

#include <algorithm>
#include <cmath>

namespace semnav
{

namespace
{
using O = SweepAssembler::TOptions;
const OptionTable<O>& optionTable()
{
	static const auto t =
	    OptionTable<O>()
	        .text(
	            "sensor_label", &O::sensorLabel,
	            "Only lines with this sensorLabel; empty = the first seen.")
	        .angle(
	            "same_tilt_tolerance_deg", &O::sameTiltTolerance, 0, 5,
	            "Tilts closer than this are the same line.")
	        .real(
	            "min_valid_range_m", &O::minValidRange, 0, 10,
	            "Returns closer than this are the robot itself.")
	        .angle(
	            "nominal_span_deg", &O::nominalSpan, 0, 180,
	            "Tilt span of a complete sweep; 0 = the largest seen.")
	        .real(
	            "complete_span_fraction", &O::completeSpanFraction, 0, 1,
	            "Sweeps spanning less of it are incomplete.")
	        .flag(
	            "split_on_motion", &O::splitOnMotion,
	            "End a sweep when the odometry moves (stop-and-scan).")
	        .flag(
	            "drop_motion_fragments", &O::dropMotionFragments,
	            "Drop incomplete sweeps cut by motion or begun after it (taken "
	            "while driving).")
	        .real(
	            "motion_tolerance_m", &O::motionTolerance, 0, 10,
	            "Odometry moves below this are no motion...")
	        .angle(
	            "motion_tolerance_deg", &O::motionToleranceYaw, 0, 180,
	            "...nor turns below this.");
	return t;
}
}  // namespace

SEMNAV_OPTIONS_FROM_TABLE(SweepAssembler::TOptions, optionTable())

SweepAssembler::SweepAssembler() : SweepAssembler(TOptions()) {}

SweepAssembler::SweepAssembler(const TOptions& options)
    : mrpt::system::COutputLogger("SweepAssembler"),
      m_options(options),
      m_label(options.sensorLabel)
{
}

void SweepAssembler::push(const mrpt::obs::CObservation::Ptr& obs)
{
	if (!obs) return;
	if (auto scan =
	        std::dynamic_pointer_cast<mrpt::obs::CObservation2DRangeScan>(obs))
	{
		if (m_label.empty()) m_label = scan->sensorLabel;
		if (scan->sensorLabel != m_label)
		{
			m_linesIgnored++;
			return;
		}
		pushLine(scan);
	}
	else if (
	    auto odo =
	        std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(obs))
	{
		pushOdometry(odo->odometry);
	}
}

void SweepAssembler::pushOdometry(const mrpt::poses::CPose2D& odometry)
{
	// Against the sweep's first reading: a slow drive moves little between
	// two readings but far during a sweep. (A sweep begun before any reading:
	// against the previous one.)
	const auto& reference = m_sweepOdometry ? m_sweepOdometry : m_odometry;
	if (m_options.splitOnMotion && reference && !m_lines.empty())
	{
		const auto d = odometry - *reference;
		if (d.norm() > m_options.motionTolerance ||
		    std::abs(mrpt::math::wrapToPi(d.phi())) >
		        m_options.motionToleranceYaw)
		{
			closeSweep(EndReason::Motion);
			m_afterMotion = true;
		}
	}
	m_odometry = odometry;
}

void SweepAssembler::pushLine(
    const mrpt::obs::CObservation2DRangeScan::Ptr& scan)
{
	const Line line{tiltOfSensorPose(scan->sensorPose), scan};
	if (!std::isfinite(line.theta))
	{
		MRPT_LOG_WARN("scan line with a non-finite sensor pose: ignored");
		return;
	}
	if (m_lines.empty())
	{
		startSweep({line});
		return;
	}
	if (scan->getScanSize() != m_lines.front().scan->getScanSize())
	{
		MRPT_LOG_WARN_FMT(
		    "scan line with %u beams in a sweep of %u beams: sweep ended",
		    static_cast<unsigned>(scan->getScanSize()),
		    static_cast<unsigned>(m_lines.front().scan->getScanSize()));
		closeSweep(EndReason::Other);
		startSweep({line});
		return;
	}
	const double d = line.theta - m_lines.back().theta;
	if (std::abs(d) <= m_options.sameTiltTolerance)
	{
		if (m_pending) m_repeated++;
		m_pending = line;
		return;
	}
	const int dir = d > 0 ? 1 : -1;
	if (m_direction == 0 || dir == m_direction)
	{
		if (m_pending)
		{
			m_repeated++;
			m_pending.reset();
		}
		m_direction = dir;
		m_lines.push_back(line);
		return;
	}
	// Reversal: the pending repeat of the end tilt opens the new sweep.
	std::vector<Line> next;
	if (m_pending) next.push_back(*m_pending);
	m_pending.reset();
	next.push_back(line);
	closeSweep(EndReason::Reversal);
	startSweep(std::move(next));
}

void SweepAssembler::startSweep(std::vector<Line> lines)
{
	m_lines = std::move(lines);
	m_direction = 0;
	if (m_lines.size() >= 2)
		m_direction = m_lines.back().theta > m_lines.front().theta ? 1 : -1;
	m_repeated = 0;
	m_sweepOdometry = m_odometry;
	m_startedAfterMotion = m_afterMotion;
	m_afterMotion = false;
}

void SweepAssembler::finish()
{
	closeSweep(EndReason::Other);
}

void SweepAssembler::closeSweep(EndReason why)
{
	if (m_pending)
	{
		m_repeated++;
		m_pending.reset();
	}
	if (m_lines.empty()) return;
	if (isMotionFragment(why))
		m_droppedMoving++;
	else
		m_ready.push_back(build(m_lines, why));
	m_lines.clear();
	m_direction = 0;
	m_repeated = 0;
}

bool SweepAssembler::isMotionFragment(EndReason why) const
{
	if (!m_options.dropMotionFragments) return false;
	// A sweep cut by the end of the stream is kept (and flagged).
	const bool driving = why == EndReason::Motion ||
	                     (why == EndReason::Reversal && m_startedAfterMotion);
	if (!driving) return false;
	double lo = m_lines.front().theta, hi = lo;
	for (const Line& l : m_lines)
	{
		lo = std::min(lo, l.theta);
		hi = std::max(hi, l.theta);
	}
	return !spanIsComplete(hi - lo);
}

bool SweepAssembler::spanIsComplete(double span) const
{
	const double reference = referenceSpan();
	return span >= m_options.completeSpanFraction * reference - 1e-9;
}

Sweep SweepAssembler::pop()
{
	Sweep s = std::move(m_ready.front());
	m_ready.pop_front();
	return s;
}

Sweep SweepAssembler::build(const std::vector<Line>& lines, EndReason why)
{
	std::vector<Line> sorted = lines;
	std::sort(
	    sorted.begin(), sorted.end(),
	    [](const Line& a, const Line& b) { return a.theta < b.theta; });
	const double span = sorted.back().theta - sorted.front().theta;

	// Nominal tilt step: median gap between consecutive lines.
	double step = 0;
	if (sorted.size() >= 2)
	{
		std::vector<double> gaps;
		for (std::size_t i = 1; i < sorted.size(); i++)
			gaps.push_back(sorted[i].theta - sorted[i - 1].theta);
		std::nth_element(
		    gaps.begin(), gaps.begin() + gaps.size() / 2, gaps.end());
		step = gaps[gaps.size() / 2];
	}
	// At most 4 rows per line: a tiny median gap (same_tilt_tolerance_deg
	// = 0) would otherwise size the sweep without bound.
	const double maxRows = 4.0 * sorted.size();
	if (step > 0 && span / step + 1 > maxRows) step = span / (maxRows - 1);
	const std::size_t rows =
	    step > 0 ? static_cast<std::size_t>(std::lround(span / step)) + 1 : 1;

	const auto& first = *lines.front().scan;
	const std::size_t cols = first.getScanSize();
	Sweep sw(rows, cols);
	std::vector<double> phi(cols);
	for (std::size_t c = 0; c < cols; c++)
	{
		const double k = cols > 1 ? static_cast<double>(c) / (cols - 1) : 0.5;
		phi[c] = -0.5 * first.aperture + k * first.aperture;
	}
	sw.setPhis(phi);
	sw.setSensorLabel(first.sensorLabel);
	sw.setTimestamp(first.timestamp);
	sw.setMaxRange(first.maxRange);
	sw.setIndex(m_emitted);
	if (m_sweepOdometry) sw.setOdometry(*m_sweepOdometry);

	std::vector<bool> filled(rows, false);
	std::size_t repeated = m_repeated;
	for (const Line& l : sorted)
	{
		const std::size_t r =
		    step > 0 ? static_cast<std::size_t>(
		                   std::lround((l.theta - sorted.front().theta) / step))
		             : 0;
		if (r >= rows || filled[r])
		{
			repeated++;
			continue;
		}
		filled[r] = true;
		sw.setRow(r, l.theta, l.scan->sensorPose);
		const auto& s = *l.scan;
		for (std::size_t c = 0; c < cols; c++)
		{
			// Column 0 is the rightmost bearing whatever the beam order.
			const std::size_t b = s.rightToLeft ? c : cols - 1 - c;
			const float rg = s.getScanRange(b);
			const bool ok = s.getScanRangeValidity(b) && rg > 0 &&
			                rg < s.maxRange && rg >= m_options.minValidRange;
			sw.setRange(r, c, rg, ok);
		}
	}
	// Rows without a line keep the interpolated tilt so geometry stays
	// monotonic; their pixels stay invalid.
	std::size_t missing = 0;
	for (std::size_t r = 0; r < rows; r++)
	{
		if (filled[r]) continue;
		missing++;
		const double theta = sorted.front().theta + r * step;
		sw.setRow(
		    r, theta,
		    tiltedSensorPose(
		        sorted.front().scan->sensorPose.translation(), theta));
	}

	m_largestSpan = std::max(m_largestSpan, span);
	const double reference = referenceSpan();
	auto& q = sw.quality();
	q.ascending = lines.back().theta >= lines.front().theta;
	q.missingLines = missing;
	q.repeatedLines = repeated;
	q.complete = spanIsComplete(span);
	// A sweep cut because the robot moved is expected while it drives.
	if (!q.complete)
		INTERNAL_MRPT_LOG_FMT(
		    why == EndReason::Motion ? mrpt::system::LVL_DEBUG
		                             : mrpt::system::LVL_WARN,
		    "sweep %u incomplete: tilt span %.1f deg of %.1f deg (%s)",
		    static_cast<unsigned>(m_emitted), mrpt::RAD2DEG(span),
		    mrpt::RAD2DEG(reference),
		    why == EndReason::Motion     ? "robot moved"
		    : why == EndReason::Reversal ? "head reversed early"
		                                 : "stream ended");
	// A few lines lost to a busy link are routine; many are not.
	if (missing > 0)
		INTERNAL_MRPT_LOG_FMT(
		    missing * 20 > lines.size() ? mrpt::system::LVL_WARN
		                                : mrpt::system::LVL_INFO,
		    "sweep %u: %u missing scan lines", static_cast<unsigned>(m_emitted),
		    static_cast<unsigned>(missing));
	m_emitted++;
	return sw;
}

}  // namespace semnav
