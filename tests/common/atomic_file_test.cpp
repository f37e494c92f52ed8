/* semnav: semantic navigation from tilting-laser sweeps */
#include <gtest/gtest.h>
#include <semnav/common/AtomicFile.h>
#include <semnav/common/Error.h>

#include <filesystem>
#include <fstream>
#include <sstream>

using namespace semnav;
namespace fs = std::filesystem;

namespace
{
std::string slurp(const fs::path& p)
{
	std::ifstream f(p);
	std::stringstream ss;
	ss << f.rdbuf();
	return ss.str();
}
}  // namespace

TEST(AtomicFile, ReplacesOnSuccessKeepsOldOnFailure)
{
	const fs::path dir = fs::temp_directory_path() /
	                     ("semnav_atomic_" + std::to_string(::getpid()));
	fs::remove_all(dir);
	createDirectories((dir / "a" / "b").string());
	const auto path = (dir / "a" / "b" / "f.txt").string();
	writeFileAtomically(path, "first");
	EXPECT_EQ(slurp(path), "first");
	EXPECT_THROW(
	    writeAtomically(
	        path,
	        [](const std::string& tmp)
	        {
		        std::ofstream(tmp) << "half";
		        throw IoError("disk full");
	        }),
	    IoError);
	EXPECT_EQ(slurp(path), "first") << "old file lost on a failed write";
	std::size_t files = 0;
	for (const auto& e : fs::directory_iterator(dir / "a" / "b"))
		files += e.is_regular_file();
	EXPECT_EQ(files, 1u) << "temporary file left behind";
	fs::remove_all(dir);
}
