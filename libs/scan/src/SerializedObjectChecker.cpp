/* semnav: semantic navigation from tilting-laser sweeps */
#include "SerializedObjectChecker.h"

#include <semnav/scan/RawlogObjectReader.h>

#include <cctype>
#include <cstdio>
#include <cstring>

namespace semnav
{
namespace
{
constexpr std::size_t kFloat = 4, kDouble = 8, kTimestamp = 8;
constexpr std::uint8_t kEndFlag = 0x88;
constexpr std::uint8_t kNewFormat = 0x80;
constexpr std::size_t kMaxClassName = 120;

/** Class name without MRPT's namespace ("mrpt::obs::X" or "X" -> "X"). */
std::string shortName(const std::string& name)
{
	const auto p = name.rfind("::");
	return p == std::string::npos ? name : name.substr(p + 2);
}
}  // namespace

bool SerializedObjectChecker::readObject()
{
	m_bytes.clear();
	m_class.clear();
	std::uint8_t first;
	if (m_source.read(&first, 1) == 0) return false;
	m_bytes.push_back(first);
	m_firstByte = first;
	object(Slot::TopLevel, true);
	return true;
}

const std::uint8_t* SerializedObjectChecker::take(std::size_t n)
{
	if (n > RawlogObjectReader::kMaxObjectBytes - m_bytes.size())
		fail(
		    "object larger than " +
		    std::to_string(RawlogObjectReader::kMaxObjectBytes >> 20) + " MB");
	const std::size_t at = m_bytes.size();
	m_bytes.resize(at + n);
	const std::size_t got = m_source.read(m_bytes.data() + at, n);
	if (got < n)
		throw SerializedFormatError(
		    "the data ends inside " +
		        (m_class.empty() ? std::string("an object header") : m_class),
		    true);
	return m_bytes.data() + at;
}

std::uint32_t SerializedObjectChecker::u32()
{
	std::uint32_t v;
	std::memcpy(&v, take(4), 4);  // MRPT stores little-endian, as x86
	return v;
}

bool SerializedObjectChecker::flag(const char* what)
{
	const std::uint8_t b = u8();
	if (b > 1)
		fail(
		    std::string(what) + " is " + std::to_string(b) + ", not a boolean");
	return b == 1;
}

void SerializedObjectChecker::string(const char* what)
{
	skip(count(what, RawlogObjectReader::kMaxStringBytes));
}

std::uint32_t SerializedObjectChecker::count(
    const char* what, std::uint32_t max)
{
	const std::uint32_t n = u32();
	if (n > max)
		fail(
		    std::string(what) + " " + std::to_string(n) + " (at most " +
		    std::to_string(max) + ")");
	return n;
}

void SerializedObjectChecker::fail(const std::string& what) const
{
	throw SerializedFormatError(
	    (m_class.empty() ? std::string() : m_class + ": ") + what, false);
}

void SerializedObjectChecker::object(Slot slot, bool allowNull)
{
	const Header h = header();
	if (h.name == "nullptr")
	{
		if (!allowNull) fail("a null object where one is required");
	}
	else
	{
		const std::string outer = m_class;
		m_class = h.name;
		body(h, slot);
		m_class = outer;
	}
	if (u8() != kEndFlag) fail("end-of-object marker missing after " + h.name);
}

SerializedObjectChecker::Header SerializedObjectChecker::header()
{
	// readObject() took the first byte of a top-level object already.
	const std::uint8_t lengthByte = m_firstByte >= 0 ? m_firstByte : u8();
	m_firstByte = -1;
	if (!(lengthByte & kNewFormat))
	{
		char hex[8];
		std::snprintf(hex, sizeof(hex), "0x%02x", lengthByte);
		fail(std::string("not an object header (byte ") + hex + ")");
	}
	const std::size_t length = lengthByte & ~kNewFormat;
	if (length == 0 || length > kMaxClassName)
		fail("class name of " + std::to_string(length) + " characters");
	const auto* p = take(length);
	std::string name(reinterpret_cast<const char*>(p), length);
	for (char c : name)
		if (!std::isalnum(static_cast<unsigned char>(c)) && c != ':' &&
		    c != '_')
			fail("class name is not text");
	Header h;
	h.name = shortName(name);
	if (h.name != "nullptr") h.version = u8();
	return h;
}

void SerializedObjectChecker::body(const Header& h, Slot slot)
{
	const bool observation =
	    slot == Slot::TopLevel || slot == Slot::Observation;
	if (h.name == "CObservation2DRangeScan" && observation)
		scan(h.version);
	else if (h.name == "CObservationOdometry" && observation)
		odometry(h.version);
	else if (h.name == "CSensoryFrame" && slot == Slot::TopLevel)
		sensoryFrame(h.version);
	else if (h.name == "CActionCollection" && slot == Slot::TopLevel)
		actionCollection(h.version);
	else if (h.name == "CActionRobotMovement2D" && slot == Slot::Action)
		robotMovement(h.version);
	else if (h.name == "CPose3D" && slot == Slot::Pose3D)
		pose3D(h.version);
	else if (h.name == "CPose2D" && slot == Slot::Pose2D)
		pose2D(h.version);
	else if (h.name == "CPosePDFGaussian" && slot == Slot::PosePdf)
		posePdf(h.version);
	else if (h.name == "CMatrixF" && slot == Slot::Matrix)
	{
		if (h.version != 0)
			fail("unsupported version " + std::to_string(h.version));
		const std::uint32_t rows = count("matrix rows", 16);
		matrix(rows, count("matrix columns", 16));
	}
	else
		fail(
		    "unsupported class here (semnav reads CObservation2DRangeScan, "
		    "CObservationOdometry, CSensoryFrame, CActionCollection)");
}

void SerializedObjectChecker::scan(int version)
{
	if (version > 7) fail("unsupported version " + std::to_string(version));
	skip(kFloat);  // aperture
	flag("rightToLeft");
	skip(kFloat);  // maxRange
	object(Slot::Pose3D, false);
	if (version < 6) object(Slot::Matrix, false);  // covSensorPose
	const std::uint32_t n = count("beams", RawlogObjectReader::kMaxBeams);
	skip(n * kFloat);
	if (version <= 3)
	{
		if (version >= 1) skip(n);       // validity
		if (version >= 2) skip(kFloat);  // stdError
		if (version >= 3) skip(kTimestamp);
		return;
	}
	skip(n);                             // validity
	skip(kFloat + kTimestamp + kFloat);  // stdError, time, beamAperture
	if (version >= 5)
	{
		string("sensor label length");
		skip(kDouble);  // deltaPitch
	}
	if (version >= 7 && flag("hasIntensity")) skip(n * 4);
}

void SerializedObjectChecker::odometry(int version)
{
	if (version > 2) fail("unsupported version " + std::to_string(version));
	object(Slot::Pose2D, false);
	string("sensor label length");
	skip(kTimestamp);
	if (version == 0) return;
	if (flag("hasEncodersInfo") || version < 2) skip(8);  // two int32
	const bool velocities = flag("hasVelocities");
	if (version < 2)
		skip(2 * kFloat);
	else if (velocities)
		skip(3 * kDouble);  // TTwist2D
}

void SerializedObjectChecker::sensoryFrame(int version)
{
	if (version > 2) fail("unsupported version " + std::to_string(version));
	if (version < 2) skip(4);  // ID
	if (version == 0) skip(kTimestamp);
	const std::uint32_t n =
	    count("observations", RawlogObjectReader::kMaxFrameObservations);
	for (std::uint32_t i = 0; i < n; i++) object(Slot::Observation, false);
}

void SerializedObjectChecker::actionCollection(int version)
{
	if (version != 0) fail("unsupported version " + std::to_string(version));
	const std::uint32_t n = count("actions", RawlogObjectReader::kMaxActions);
	for (std::uint32_t i = 0; i < n; i++) object(Slot::Action, false);
}

void SerializedObjectChecker::robotMovement(int version)
{
	if (version < 4 || version > 7)
		fail("unsupported version " + std::to_string(version));
	const std::int32_t method = i32();
	if (method != 0 && method != 1)
		fail("estimation method " + std::to_string(method));
	if (method == 0)  // emOdometry: the PDF is rebuilt from the model
	{
		object(Slot::Pose2D, false);
		const std::int32_t model = i32();
		if (model != 0 && model != 1)
			fail("motion model " + std::to_string(model));
		skip(6 * kFloat);  // Gaussian model
		const std::int32_t particles = i32();
		if (particles < 0 || static_cast<std::uint32_t>(particles) >
		                         RawlogObjectReader::kMaxParticles)
			fail(
			    "particles " + std::to_string(particles) + " (at most " +
			    std::to_string(RawlogObjectReader::kMaxParticles) + ")");
		skip(4 * kFloat);  // Thrun model
		if (version >= 5) skip(2 * kFloat);
	}
	else
		object(Slot::PosePdf, false);
	const bool velocities = flag("hasVelocities");
	if (version < 7)
		skip(2 * kFloat);
	else if (velocities)
		skip(3 * kDouble);
	if (flag("hasEncodersInfo") || version < 7) skip(8);
	if (version >= 6) skip(kTimestamp);
}

void SerializedObjectChecker::pose3D(int version)
{
	if (version == 2)
		skip(7 * kDouble);  // x y z + quaternion
	else if (version == 3)
		skip(12 * kDouble);  // x y z + rotation matrix
	else
		fail("unsupported version " + std::to_string(version));
}

void SerializedObjectChecker::pose2D(int version)
{
	if (version > 1) fail("unsupported version " + std::to_string(version));
	skip(3 * (version == 0 ? kFloat : kDouble));
}

void SerializedObjectChecker::posePdf(int version)
{
	if (version > 2) fail("unsupported version " + std::to_string(version));
	object(Slot::Pose2D, false);
	if (version == 0)
	{
		// The covariance as a CMatrixF, which MRPT copies into a 3 x 3.
		const Header h = header();
		if (h.name != "CMatrixF" || h.version != 0)
			fail("covariance is not a CMatrixF");
		if (count("covariance rows", 3) != 3 ||
		    count("covariance columns", 3) != 3)
			fail("covariance is not 3 x 3");
		matrix(3, 3);
		if (u8() != kEndFlag) fail("end-of-object marker missing");
	}
	else
		skip(6 * (version == 1 ? kFloat : kDouble));  // upper triangle
}

void SerializedObjectChecker::matrix(std::uint32_t rows, std::uint32_t cols)
{
	skip(static_cast<std::size_t>(rows) * cols * kFloat);
}

}  // namespace semnav
