/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

// A scripted SweepSource for the navigation tests: sweeps of the paper's
// tilting LMS200 computed analytically in a room of axis-aligned boxes,
// where the fake base truly stands; no simulator behind it.

#include <mrpt/math/TPoint3D.h>
#include <mrpt/poses/CPose3D.h>
#include <semnav/scan/SweepSource.h>
#include <semnav/scan/TiltGeometry.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "FakeRobot.h"

namespace semnav::test
{
/** A room of axis-aligned boxes (walls, floor, ceiling, furniture). */
struct FakeRoom
{
	struct Box
	{
		mrpt::math::TPoint3D lo, hi;
	};
	std::vector<Box> boxes;

	/** Range along the unit ray o + t d to the nearest box face (slab
	 * test); nothing when no box is hit within maxRange. */
	std::optional<double> cast(
	    const mrpt::math::TPoint3D& o, const mrpt::math::TPoint3D& d,
	    double maxRange) const
	{
		double best = maxRange;
		bool hit = false;
		for (const auto& b : boxes)
		{
			double t0 = 0, t1 = best;
			bool miss = false;
			for (int k = 0; k < 3 && !miss; k++)
			{
				if (std::abs(d[k]) < 1e-12)
				{
					miss = o[k] < b.lo[k] || o[k] > b.hi[k];
					continue;
				}
				double a = (b.lo[k] - o[k]) / d[k], c = (b.hi[k] - o[k]) / d[k];
				if (a > c) std::swap(a, c);
				t0 = std::max(t0, a);
				t1 = std::min(t1, c);
				miss = t0 > t1;
			}
			if (!miss && t0 > 1e-9)
			{
				best = t0;
				hit = true;
			}
		}
		if (!hit) return std::nullopt;
		return best;
	}

	/** True when a disc of `radius` at (x, y) overlaps a box between
	 * heights zLo and zHi. */
	bool blocks(double x, double y, double radius, double zLo, double zHi) const
	{
		for (const auto& b : boxes)
		{
			if (b.hi.z <= zLo || b.lo.z >= zHi) continue;
			const double dx = std::max({b.lo.x - x, 0.0, x - b.hi.x});
			const double dy = std::max({b.lo.y - y, 0.0, y - b.hi.y});
			if (std::hypot(dx, dy) < radius) return true;
		}
		return false;
	}
};

/** A 7 m x 5 m room (inner faces at x = 0, 7 and y = 0, 5), walls 2.5 m
 * high, floor and ceiling; a partition 1.8 m into the room from the
 * y = 0 wall at x = 4.5, a pillar and two low boxes make it asymmetric. */
inline FakeRoom asymmetricRoom()
{
	constexpr double H = 2.5, T = 0.15;
	FakeRoom r;
	const auto box = [&](double x0, double y0, double z0, double x1, double y1,
	                     double z1) {
		r.boxes.push_back({{x0, y0, z0}, {x1, y1, z1}});
	};
	box(-T, -T, -0.1, 7 + T, 5 + T, 0);     // floor
	box(-T, -T, H, 7 + T, 5 + T, H + 0.1);  // ceiling
	box(-T, -T, 0, 0, 5 + T, H);            // walls
	box(7, -T, 0, 7 + T, 5 + T, H);
	box(0, -T, 0, 7, 0, H);
	box(0, 5, 0, 7, 5 + T, H);
	box(4.5, 0, 0, 4.65, 1.8, H);      // partition
	box(1.3, 3.4, 0, 1.7, 3.8, H);     // pillar
	box(5.5, 3.6, 0, 6.1, 4.0, 0.75);  // boxes
	box(2.6, 0.5, 0, 3.1, 1.0, 0.5);
	return r;
}

/** Sweeps of the tilting LMS200 in a FakeRoom from the fake base's true
 * pose, as a SweepSource. The geometry is the paper's and semnav-sim's:
 * tilt theta from -15 to 90 deg in 0.5 deg lines, row r's scanner pose
 * tiltedSensorPose(mount, theta_r, phiCenter); 361 beams from -90 to
 * 90 deg with MRPT's layout (bearing of beam c = phi_c - phiCenter, the
 * scanner's x axis at the centre of the field of view); max range 8 m,
 * Gaussian range noise. Each next() advances the clock by the sweep time
 * (lines x line period; the base keeps its command, so it must be stopped)
 * and records whether the base was stopped before and stood still during
 * the sweep, and whether it began at or after next()'s notBefore (the fake
 * does not wait for a later one). The script can lose the device after
 * some sweeps. */
class ScriptedSweepSource : public SweepSource
{
public:
	struct Script
	{
		/** next() fails with End::DeviceLost after this many sweeps
		 * (negative: never). */
		int deviceLostAfter = -1;
		double linePeriod = 1.0 / 75;
		double rangeNoise = 0.005;
		unsigned seed = 1;
	};

	/** What one next() saw. */
	struct Taken
	{
		double start = 0, end = 0;
		mrpt::math::TPose2D truth;
		/** No velocity command in force when the sweep began. */
		bool stoppedBefore = false;
		/** The true pose did not change during the sweep. */
		bool stillDuring = false;
		/** The sweep began at or after next()'s notBefore. */
		bool notBeforeMet = false;
	};

	ScriptedSweepSource(
	    FakeBase& base, ControlClock& clock, const FakeRoom& room,
	    const Script& script)
	    : m_base(base), m_clock(clock), m_room(room), m_script(script)
	{
	}

	/** Called with every sweep returned (e.g. SweepObstacles::update). */
	void onSweep(std::function<void(const Sweep&)> f)
	{
		m_onSweep = std::move(f);
	}

	bool next(Sweep& sweep, mrpt::Clock::time_point notBefore = {}) override
	{
		if (m_cancelled) return endWith(End::Cancelled, "cancelled");
		if (m_script.deviceLostAfter >= 0 &&
		    static_cast<int>(m_taken.size()) >= m_script.deviceLostAfter)
			return endWith(
			    End::DeviceLost, "no answer on /dev/fake-lms200 after " +
			                         std::to_string(m_taken.size()) +
			                         " sweeps (scripted)");
		Taken t;
		t.start = m_clock.now();
		t.notBeforeMet = fakeTimestamp(t.start) >= notBefore;
		t.truth = m_base.truePose();
		t.stoppedBefore = !m_base.moving();
		sweep = render(t.truth, m_taken.size());
		sweep.setTimestamp(fakeTimestamp(t.start));
		m_clock.waitFor(m_script.linePeriod * static_cast<double>(kLines));
		t.end = m_clock.now();
		const auto& after = m_base.truePose();
		t.stillDuring = std::abs(after.x - t.truth.x) < 1e-9 &&
		                std::abs(after.y - t.truth.y) < 1e-9 &&
		                std::abs(after.phi - t.truth.phi) < 1e-9;
		sweep.setOdometry(mrpt::poses::CPose2D(m_base.odometry().pose));
		m_taken.push_back(t);
		if (m_onSweep) m_onSweep(sweep);
		return true;
	}
	void cancel() override { m_cancelled = true; }
	End end() const override { return m_end; }
	std::string endMessage() const override { return m_message; }

	const std::vector<Taken>& taken() const { return m_taken; }
	/** The device is lost from now on. */
	void loseDevice()
	{
		m_script.deviceLostAfter = static_cast<int>(m_taken.size());
	}

	/** The sweep from robot pose `pose` (no odometry, no timestamp). */
	Sweep render(const mrpt::math::TPose2D& pose, std::size_t index) const
	{
		constexpr double deg = M_PI / 180;
		constexpr double maxRange = 8.0;
		const mrpt::math::TPoint3D mount{0, 0, 0.45};
		Sweep s(kLines, kBeams);
		// MRPT spreads the beams symmetrically about the scanner's x axis.
		const double phiMin = -90 * deg, phiStep = 0.5 * deg;
		const double phiCenter = phiMin + 0.5 * (kBeams - 1) * phiStep;
		std::vector<double> bearings(kBeams);
		for (std::size_t c = 0; c < kBeams; c++)
			bearings[c] = phiMin + c * phiStep - phiCenter;
		s.setPhis(bearings);
		s.setMaxRange(static_cast<float>(maxRange));
		s.setSensorLabel("TILT_LMS");
		s.setIndex(index);
		s.quality().ascending = index % 2 == 0;
		const mrpt::poses::CPose3D robot(pose.x, pose.y, 0, pose.phi, 0, 0);
		std::mt19937 rng(m_script.seed * 7919u + static_cast<unsigned>(index));
		std::normal_distribution<double> noise(0.0, m_script.rangeNoise);
		for (std::size_t r = 0; r < kLines; r++)
		{
			const double theta = (-15 + 0.5 * r) * deg;
			const auto sensor = tiltedSensorPose(mount, theta, phiCenter);
			s.setRow(r, theta, sensor);
			const mrpt::poses::CPose3D world = robot + sensor;
			const auto& R = world.getRotationMatrix();
			const mrpt::math::TPoint3D o(world.x(), world.y(), world.z());
			for (std::size_t c = 0; c < kBeams; c++)
			{
				const double cb = std::cos(bearings[c]),
				             sb = std::sin(bearings[c]);
				const mrpt::math::TPoint3D d(
				    cb * R(0, 0) + sb * R(0, 1), cb * R(1, 0) + sb * R(1, 1),
				    cb * R(2, 0) + sb * R(2, 1));
				const auto hit = m_room.cast(o, d, maxRange);
				const double meas = hit ? *hit + noise(rng) : maxRange;
				const bool valid = hit && meas > 0 && meas <= maxRange;
				s.setRange(
				    r, c, static_cast<float>(valid ? meas : maxRange), valid);
			}
		}
		return s;
	}

private:
	static constexpr std::size_t kLines = 211, kBeams = 361;

	bool endWith(End e, const std::string& message)
	{
		m_end = e;
		m_message = "fake LMS200: " + message;
		return false;
	}

	FakeBase& m_base;
	ControlClock& m_clock;
	const FakeRoom& m_room;
	Script m_script;
	std::function<void(const Sweep&)> m_onSweep;
	std::vector<Taken> m_taken;
	bool m_cancelled = false;
	End m_end = End::None;
	std::string m_message;
};

}  // namespace semnav::test
