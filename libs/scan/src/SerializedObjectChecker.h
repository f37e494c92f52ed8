/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace semnav
{
/** Where SerializedObjectChecker takes its bytes from. */
class ByteSource
{
public:
	virtual ~ByteSource() = default;
	/** Up to n bytes into dst; fewer only at the end of the data. Throws
	 * SerializedFormatError on a read error. */
	virtual std::size_t read(std::uint8_t* dst, std::size_t n) = 0;
};

/** The bytes do not hold a well-formed object of a class semnav reads. */
class SerializedFormatError : public std::runtime_error
{
public:
	SerializedFormatError(const std::string& what, bool truncated)
	    : std::runtime_error(what), m_truncated(truncated)
	{
	}
	/** The data ended inside the object. */
	bool truncated() const { return m_truncated; }

private:
	bool m_truncated;
};

/** Walks one object of MRPT's binary serialization format (header, body of
 * a known class and version, end marker), copying its bytes, and checks
 * every count against RawlogObjectReader's bounds before reading what it
 * counts. The classes and versions are MRPT 2.5's serializeFrom() of
 * CObservation2DRangeScan (0-7), CObservationOdometry (0-2),
 * CSensoryFrame (0-2), CActionCollection (0), CActionRobotMovement2D
 * (4-7), CPose3D (2-3), CPose2D (0-1), CPosePDFGaussian (0-2), CMatrixF (0).
 * Anything else throws SerializedFormatError. */
class SerializedObjectChecker
{
public:
	explicit SerializedObjectChecker(ByteSource& source) : m_source(source) {}

	/** Reads one top-level object; false when the data ends before its
	 * first byte. Its bytes are then bytes(). */
	bool readObject();
	const std::vector<std::uint8_t>& bytes() const { return m_bytes; }

private:
	enum class Slot
	{
		TopLevel,
		Observation,
		Action,
		Pose3D,
		Pose2D,
		PosePdf,
		Matrix
	};
	struct Header
	{
		std::string name;  ///< without the namespace
		int version = 0;
	};

	void object(Slot slot, bool allowNull);
	Header header();
	void body(const Header& h, Slot slot);
	void scan(int version);
	void odometry(int version);
	void sensoryFrame(int version);
	void actionCollection(int version);
	void robotMovement(int version);
	void pose3D(int version);
	void pose2D(int version);
	void posePdf(int version);
	void matrix(std::uint32_t rows, std::uint32_t cols);

	const std::uint8_t* take(std::size_t n);
	void skip(std::size_t n) { take(n); }
	std::uint8_t u8() { return *take(1); }
	std::uint32_t u32();
	std::int32_t i32() { return static_cast<std::int32_t>(u32()); }
	bool flag(const char* what);
	void string(const char* what);
	std::uint32_t count(const char* what, std::uint32_t max);
	[[noreturn]] void fail(const std::string& what) const;

	ByteSource& m_source;
	std::vector<std::uint8_t> m_bytes;
	std::string m_class;   ///< of the object being walked
	int m_firstByte = -1;  ///< taken by readObject(), not yet parsed
};

}  // namespace semnav
