/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

/** Files of the libFuzzer harnesses: readers that take a path get the fuzz
 * input written to a per-process scratch directory, and the seed corpus is
 * written where $SEMNAV_FUZZ_SEEDS says (scripts/fuzz). */
namespace semnav::fuzz
{
/** semnav_fuzz_<name>_<pid> under the temp directory, created once. */
inline std::filesystem::path scratchDir(const std::string& name)
{
	const auto d = std::filesystem::temp_directory_path() /
	               ("semnav_fuzz_" + name + "_" + std::to_string(::getpid()));
	std::filesystem::create_directories(d);
	return d;
}

inline void writeBytes(
    const std::filesystem::path& path, const void* data, std::size_t size)
{
	std::ofstream f(path, std::ios::binary | std::ios::trunc);
	f.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
}

inline std::string readBytes(const std::filesystem::path& path)
{
	std::ifstream f(path, std::ios::binary);
	return std::string(std::istreambuf_iterator<char>(f), {});
}

/** The seed directory to fill, or empty when $SEMNAV_FUZZ_SEEDS is unset. */
inline std::filesystem::path seedDir()
{
	const char* d = std::getenv("SEMNAV_FUZZ_SEEDS");
	if (d == nullptr || *d == 0) return {};
	std::filesystem::create_directories(d);
	return d;
}

/** Writes one seed `name` with `bytes` into seedDir() (when set). */
inline void writeSeed(const std::string& name, const std::string& bytes)
{
	const auto d = seedDir();
	if (!d.empty()) writeBytes(d / name, bytes.data(), bytes.size());
}
}  // namespace semnav::fuzz
