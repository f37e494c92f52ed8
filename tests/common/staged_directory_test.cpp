/* semnav: semantic navigation from tilting-laser sweeps */
// StagedDirectory (whole-directory replacement) and DatasetCompletion.
#include <gtest/gtest.h>
#include <semnav/common/DatasetCompletion.h>
#include <semnav/common/Error.h>
#include <semnav/common/StagedDirectory.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

using namespace semnav;
namespace fs = std::filesystem;

namespace
{
fs::path freshDir(const std::string& name)
{
	const fs::path d =
	    fs::temp_directory_path() /
	    ("semnav_staged_" + name + "_" + std::to_string(::getpid()));
	fs::remove_all(d);
	fs::create_directories(d);
	return d;
}

std::string slurp(const fs::path& p)
{
	std::ifstream f(p);
	std::stringstream ss;
	ss << f.rdbuf();
	return ss.str();
}

bool anyName(const std::string&)
{
	return true;
}

/** The pid of a process that has exited (not reused so soon). */
long deadPid()
{
	const pid_t pid = ::fork();
	if (pid == 0) ::_exit(0);
	int status = 0;
	::waitpid(pid, &status, 0);
	return pid;
}

/** The entries of `dir` whose names start with '.' (staging leftovers). */
std::size_t hiddenEntries(const fs::path& dir)
{
	std::size_t n = 0;
	for (const auto& e : fs::directory_iterator(dir))
		n += e.path().filename().string()[0] == '.';
	return n;
}
}  // namespace

TEST(StagedDirectory, ReplacesTheWholeDirectoryAndLeavesNothingBeside)
{
	const fs::path root = freshDir("replace");
	const fs::path target = root / "map";
	fs::create_directories(target / "sub");
	std::ofstream(target / "old_only.txt") << "old";
	std::ofstream(target / "both.txt") << "old";
	{
		StagedDirectory s(target.string() + "/", anyName);
		EXPECT_TRUE(fs::is_empty(s.path()));
		std::ofstream(fs::path(s.path()) / "both.txt") << "new";
		// Until commit() the target is the old directory.
		EXPECT_EQ(slurp(target / "both.txt"), "old");
		s.commit();
	}
	EXPECT_EQ(slurp(target / "both.txt"), "new");
	EXPECT_FALSE(fs::exists(target / "old_only.txt"));
	EXPECT_FALSE(fs::exists(target / "sub"));
	EXPECT_EQ(hiddenEntries(root), 0u);
	fs::remove_all(root);
}

TEST(StagedDirectory, UncommittedLeavesTheTargetAlone)
{
	const fs::path root = freshDir("abort");
	fs::create_directories(root / "map");
	std::ofstream(root / "map" / "a.txt") << "old";
	{
		StagedDirectory s((root / "map").string(), anyName);
		std::ofstream(fs::path(s.path()) / "a.txt") << "new";
	}
	EXPECT_EQ(slurp(root / "map" / "a.txt"), "old");
	EXPECT_EQ(hiddenEntries(root), 0u);
	fs::remove_all(root);
}

TEST(StagedDirectory, RefusesToDeleteWhatIsNotItsOwn)
{
	const fs::path root = freshDir("foreign");
	fs::create_directories(root / "out");
	std::ofstream(root / "out" / "thesis.tex") << "precious";
	StagedDirectory s(
	    (root / "out").string(),
	    [](const std::string& n) { return n == "map.yaml"; });
	try
	{
		s.commit();
		FAIL() << "replaced a directory holding thesis.tex";
	}
	catch (const IoError& e)
	{
		EXPECT_NE(std::string(e.what()).find("thesis.tex"), std::string::npos)
		    << e.what();
	}
	EXPECT_EQ(slurp(root / "out" / "thesis.tex"), "precious");
	EXPECT_THROW(StagedDirectory(".", anyName), IoError);
	fs::remove_all(root);
}

TEST(StagedDirectory, LeftoversOfDeadWritersAreNamedThenCleanedUp)
{
	const fs::path root = freshDir("dead");
	const long pid = deadPid();
	const std::string suffix = "-" + std::to_string(pid);
	// A writer killed between the two renames of the fallback: no target, a
	// complete "ready" directory, the old one under "new".
	fs::create_directories(root / (".map.ready" + suffix));
	std::ofstream(root / (".map.ready" + suffix) / "a.txt") << "new";
	fs::create_directories(root / (".map.new" + suffix));
	std::ofstream(root / (".map.new" + suffix) / "a.txt") << "old";
	EXPECT_EQ(
	    StagedDirectory::interruptedSave((root / "map").string()),
	    (root / (".map.ready" + suffix)).string());
	{
		// The next writer recovers the complete directory first.
		StagedDirectory s((root / "map").string(), anyName);
		EXPECT_EQ(slurp(root / "map" / "a.txt"), "new");
		EXPECT_EQ(hiddenEntries(root), 1u);  // its own staging directory
	}
	EXPECT_EQ(hiddenEntries(root), 0u);
	EXPECT_EQ(StagedDirectory::interruptedSave((root / "map").string()), "");
	fs::remove_all(root);
}

TEST(DatasetCompletion, AnUnfinishedDatasetIsRefusedInOneLine)
{
	const fs::path root = freshDir("dataset");
	EXPECT_NO_THROW(DatasetCompletion::require(root.string(), "office"));
	DatasetCompletion::begin(root.string(), "office");
	try
	{
		DatasetCompletion::require(root.string(), "office");
		FAIL() << "an incomplete dataset passed";
	}
	catch (const IoError& e)
	{
		const std::string m = e.what();
		EXPECT_NE(m.find("office"), std::string::npos) << m;
		EXPECT_NE(m.find("incomplete"), std::string::npos) << m;
		EXPECT_EQ(m.find('\n'), std::string::npos) << m;
	}
	EXPECT_NO_THROW(DatasetCompletion::require(root.string(), "other"));
	DatasetCompletion::end(root.string(), "office");
	EXPECT_NO_THROW(DatasetCompletion::require(root.string(), "office"));
	fs::remove_all(root);
}
