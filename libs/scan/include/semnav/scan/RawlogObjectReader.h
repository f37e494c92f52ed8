/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/serialization/CSerializable.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

namespace semnav
{
/** Reads the serialized objects of a rawlog (gzip or plain) one at a time,
 * safely: the bytes of each object are first walked against the layout of
 * the classes semnav reads (CObservation2DRangeScan, CObservationOdometry,
 * CSensoryFrame, CActionCollection with CActionRobotMovement2D), every
 * count and length bounded before anything is allocated, and only then
 * handed to MRPT, which deserializes them from memory
 * (docs/design.md, "Reading rawlogs safely").
 *
 * Corrupt or truncated data, an unsupported class or version, or a gzip
 * error throws RawlogError naming the file, the object's index and its byte
 * offset in the decompressed stream; memory stays bounded by kMaxObjectBytes
 * whatever the file holds. */
class RawlogObjectReader
{
public:
	/** Bounds of what a rawlog may hold (a 2D scanner has at most a few
	 * thousand beams). */
	static constexpr std::uint32_t kMaxBeams = 65536;
	static constexpr std::uint32_t kMaxStringBytes = 4096;
	static constexpr std::uint32_t kMaxFrameObservations = 4096;
	static constexpr std::uint32_t kMaxActions = 64;
	static constexpr std::uint32_t kMaxParticles = 100000;
	static constexpr std::size_t kMaxObjectBytes = 64u << 20;

	/** Throws RawlogError when the file cannot be opened. */
	explicit RawlogObjectReader(const std::string& path);
	~RawlogObjectReader();

	/** Reads the next object into `obj` (null for a stored null object);
	 * false at the clean end of the file. Throws RawlogError as above; after
	 * a throw, next() returns false. */
	bool next(mrpt::serialization::CSerializable::Ptr& obj);

	/** Objects read so far. */
	std::size_t objectsRead() const { return m_objects; }
	/** Offset of the next object in the decompressed stream (bytes). */
	std::uint64_t offset() const { return m_offset; }
	const std::string& path() const { return m_path; }

private:
	class Input;
	std::string m_path;
	std::unique_ptr<Input> m_in;
	std::size_t m_objects = 0;
	std::uint64_t m_offset = 0;
	bool m_done = false;
};

}  // namespace semnav
