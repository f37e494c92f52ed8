/* semnav: semantic navigation from tilting-laser sweeps */
// Outputs replaced as a whole: semnav-map killed (SIGKILL) at random moments
// while overwriting a map leaves a directory that loads (MapIO, as
// semnav-plan loads it) as the complete old map or the complete new one;
// semnav-sim killed while overwriting a dataset leaves the complete old or
// new dataset, or one its readers refuse in one line; semnav-nav leaves no
// .navlog-<pid>/ when it fails or is terminated.
//
// SEMNAV_KILL_TRIALS (default 8 per app) and SEMNAV_KILL_SEED (default 1)
// set the number of kills and their seed (scripts/kill-overwrites runs 50).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <octomap/OcTree.h>
#include <semnav/common/DatasetCompletion.h>
#include <semnav/common/Error.h>
#include <semnav/map/MapIO.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/scan/GroundTruthLog.h>
#include <semnav/scan/RawlogSweepReader.h>
#include <semnav/sim/SceneLoader.h>
#include <semnav/sim/SimulationRunner.h>
#include <semnav/training/PerceptionRun.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <sstream>
#include <thread>

#include "../TestPaths.h"
#include "AppRunner.h"

using namespace semnav;
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

extern char** environ;

namespace
{
const bool kVerbose = std::getenv("SEMNAV_KILL_VERBOSE") != nullptr;

int envInt(const char* name, int fallback)
{
	const char* v = std::getenv(name);
	return v && *v ? std::atoi(v) : fallback;
}

fs::path tmpDir(const std::string& name)
{
	const fs::path d =
	    fs::temp_directory_path() /
	    ("semnav_atomic_" + name + "_" + std::to_string(::getpid()));
	fs::remove_all(d);
	fs::create_directories(d);
	return d;
}

/** datasets/nav/utrap.yaml named `name`, with the first `poses` poses of
 * `trajectory` (small, so that a whole run takes about a second). */
fs::path writeScene(
    const fs::path& dir, const std::string& name,
    const std::vector<std::string>& trajectory)
{
	std::ifstream in(test::kSourceDir + "/datasets/nav/utrap.yaml");
	std::stringstream ss;
	ss << in.rdbuf();
	std::string text = ss.str();
	text = text.substr(0, text.find("trajectory:"));
	text.replace(text.find("name: utrap"), 11, "name: " + name);
	text += "trajectory:\n";
	for (const auto& p : trajectory) text += "  - " + p + "\n";
	const fs::path file =
	    dir / (name + "_" + std::to_string(trajectory.size()) + ".yaml");
	std::ofstream(file) << text;
	return file;
}

/** One app run: started, optionally killed, reaped. */
class AppProcess
{
public:
	AppProcess(const std::string& app, std::vector<std::string> args)
	{
		const std::string exe =
		    std::string(SEMNAV_BINARY_DIR) + "/apps/" + app + "/" + app;
		args.insert(args.begin(), exe);
		std::vector<char*> argv;
		for (auto& a : args) argv.push_back(a.data());
		argv.push_back(nullptr);
		posix_spawn_file_actions_t fa;
		posix_spawn_file_actions_init(&fa);
		posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
		posix_spawn_file_actions_addopen(&fa, 2, "/dev/null", O_WRONLY, 0);
		m_start = Clock::now();
		if (posix_spawn(
		        &m_pid, exe.c_str(), &fa, nullptr, argv.data(), environ) != 0)
			m_pid = -1;
		posix_spawn_file_actions_destroy(&fa);
	}
	pid_t pid() const { return m_pid; }
	double elapsed() const
	{
		return std::chrono::duration<double>(Clock::now() - m_start).count();
	}
	/** Waits until `ready()` or the process ends; true if ready. */
	template <typename F>
	bool waitUntil(F&& ready)
	{
		while (!m_done)
		{
			if (ready()) return true;
			reap(WNOHANG);
			std::this_thread::sleep_for(std::chrono::microseconds(200));
		}
		return ready();
	}
	bool waitFor(const fs::path& path)
	{
		return waitUntil([&] { return fs::exists(path); });
	}
	void sleepThenKill(double seconds)
	{
		const auto until =
		    Clock::now() + std::chrono::duration_cast<Clock::duration>(
		                       std::chrono::duration<double>(seconds));
		while (!m_done && Clock::now() < until)
		{
			reap(WNOHANG);
			std::this_thread::sleep_for(std::chrono::microseconds(200));
		}
		if (!m_done) ::kill(m_pid, SIGKILL);
	}
	/** Exit status (-signal when killed). */
	int wait()
	{
		reap(0);
		return m_status;
	}

private:
	void reap(int flags)
	{
		if (m_done) return;
		int st = 0;
		if (::waitpid(m_pid, &st, flags) == m_pid)
		{
			m_done = true;
			m_status = WIFEXITED(st) ? WEXITSTATUS(st) : -WTERMSIG(st);
		}
	}
	pid_t m_pid = -1;
	Clock::time_point m_start;
	bool m_done = false;
	int m_status = 0;
};

uint64_t fnv(uint64_t h, const void* data, std::size_t n)
{
	const auto* p = static_cast<const unsigned char*>(data);
	for (std::size_t i = 0; i < n; i++) h = (h ^ p[i]) * 1099511628211ull;
	return h;
}

uint64_t fnv(uint64_t h, const std::string& s)
{
	return fnv(h, s.data(), s.size());
}

/** A digest of everything MapIO::load gives: every layer, the occupancy,
 * the objects, the sweep count and the OctoMap. */
uint64_t mapDigest(const fs::path& dir)
{
	SemanticMap m;
	MapIO::load(dir.string(), m);
	uint64_t h = 1469598103934665603ull;
	for (const auto& name : m.layers())
	{
		const auto& v = m.get(name);
		h = fnv(fnv(h, name), v.data(), v.size() * sizeof(float));
	}
	const auto& raw = m.occupancyGrid().getRawMap();
	h = fnv(h, raw.data(), raw.size() * sizeof(raw[0]));
	for (const auto& o : m.allInstances())
	{
		const double c[3] = {o.centroid.x, o.centroid.y, o.centroid.z};
		h = fnv(fnv(h, &o.id, sizeof(o.id)), c, sizeof(c));
		h = fnv(h, labelName(o.label));
	}
	const std::size_t counts[2] = {m.sweepsInserted(), m.octree().size()};
	return fnv(h, counts, sizeof(counts));
}

std::string slurp(const fs::path& p)
{
	std::ifstream f(p, std::ios::binary);
	std::stringstream ss;
	ss << f.rdbuf();
	return ss.str();
}

/** A digest of a dataset as its readers pair it: the ground truth, the
 * label images and the number of sweeps in the rawlog. */
uint64_t datasetDigest(const fs::path& dir, const std::string& name)
{
	uint64_t h = fnv(1469598103934665603ull, slurp(dir / (name + ".gt.txt")));
	std::vector<fs::path> images;
	for (const auto& e : fs::directory_iterator(dir / (name + ".labels")))
		images.push_back(e.path());
	std::sort(images.begin(), images.end());
	for (const auto& p : images) h = fnv(h, slurp(p));
	RawlogSweepReader reader((dir / (name + ".rawlog")).string());
	Sweep s;
	std::size_t sweeps = 0;
	while (reader.next(s)) sweeps++;
	return fnv(h, &sweeps, sizeof(sweeps));
}

/** Names in `dir`. */
std::set<std::string> entries(const fs::path& dir)
{
	std::set<std::string> names;
	for (const auto& e : fs::directory_iterator(dir))
		names.insert(e.path().filename().string());
	return names;
}

/** Whether the save began, whichever way it writes: a name appeared beside
 * `target` or a file in it changed since `since`. */
struct SaveBegan
{
	fs::path target;
	std::set<std::string> before = entries(target.parent_path());
	fs::file_time_type since = fs::file_time_type::clock::now();
	bool operator()() const;
};

bool SaveBegan::operator()() const
{
	std::error_code ec;
	for (const auto& e : fs::directory_iterator(target.parent_path(), ec))
		if (!before.count(e.path().filename().string())) return true;
	for (const auto& e : fs::recursive_directory_iterator(target, ec))
		if (fs::last_write_time(e.path(), ec) > since) return true;
	return false;
}

std::size_t hiddenEntries(const fs::path& dir)
{
	std::size_t n = 0;
	for (const auto& e : fs::directory_iterator(dir))
		n += e.path().filename().string()[0] == '.';
	return n;
}

/** Two simulated rawlogs (2 and 3 stops) of one small scene. */
struct Rawlogs
{
	fs::path dir, oldRawlog, newRawlog;
};

Rawlogs rawlogs()
{
	Rawlogs out;
	out.dir = tmpDir("rawlogs");
	const std::vector<std::string> poses = {
	    "[1.5, 1.5, 0]", "[2.8, 3.9, 0]", "[5.5, 4.5, 0]"};
	for (const std::size_t n : {2u, 3u})
	{
		const auto scene = writeScene(
		    out.dir, "tiny" + std::to_string(n),
		    {poses.begin(), poses.begin() + n});
		SimulationRunner(
		    SceneLoader::loadFile(scene.string()), SimulationRunner::TOptions(),
		    1)
		    .run(out.dir.string());
	}
	out.oldRawlog = out.dir / "tiny2.rawlog";
	out.newRawlog = out.dir / "tiny3.rawlog";
	return out;
}

std::vector<std::string> mapArgs(const fs::path& rawlog, const fs::path& out)
{
	return {"--rawlog", rawlog.string(), "--out",        out.string(),
	        "--poses",  "odometry",      "--no-cascades"};
}
}  // namespace

TEST(AtomicOutputs, KilledSemnavMapLeavesTheOldOrTheNewMap)
{
	const Rawlogs r = rawlogs();
	const fs::path root = tmpDir("map");
	const fs::path oldMap = root / "old", newMap = root / "new";
	ASSERT_EQ(AppProcess("semnav-map", mapArgs(r.oldRawlog, oldMap)).wait(), 0);
	const fs::path target = root / "map";
	fs::copy(oldMap, target, fs::copy_options::recursive);
	// Calibration: a whole overwrite; when its save begins.
	const SaveBegan began{target};
	AppProcess full("semnav-map", mapArgs(r.newRawlog, target));
	ASSERT_TRUE(full.waitUntil(began));
	const double beganAt = full.elapsed();
	// It ends when the target's map.yaml (written last) is the new one.
	ASSERT_TRUE(full.waitUntil(
	    [&]
	    {
		    std::error_code ec;
		    return fs::last_write_time(target / "map.yaml", ec) > began.since;
	    }));
	const double saveSeconds = full.elapsed() - beganAt;
	ASSERT_EQ(full.wait(), 0);
	const double total = full.elapsed();
	fs::rename(target, newMap);
	const uint64_t oldDigest = mapDigest(oldMap), newDigest = mapDigest(newMap);
	ASSERT_NE(oldDigest, newDigest);

	std::mt19937 rng(static_cast<unsigned>(envInt("SEMNAV_KILL_SEED", 1)));
	const int trials = envInt("SEMNAV_KILL_TRIALS", 8);
	int keptOld = 0, gotNew = 0, duringSave = 0;
	for (int i = 0; i < trials; i++)
	{
		fs::remove_all(target);
		fs::copy(oldMap, target, fs::copy_options::recursive);
		const SaveBegan saveBegan{target};
		AppProcess p("semnav-map", mapArgs(r.newRawlog, target));
		// A quarter of the kills anywhere in the run, the rest while it saves.
		double at = 0;
		if (i % 4 == 0)
		{
			at = std::uniform_real_distribution<double>(0, total * 1.05)(rng);
			p.sleepThenKill(at);
		}
		else
		{
			p.waitUntil(saveBegan);
			duringSave++;
			at = std::uniform_real_distribution<double>(
			    0, saveSeconds * 1.2)(rng);
			p.sleepThenKill(at);
		}
		const int status = p.wait();
		uint64_t d = 0;
		ASSERT_NO_THROW(d = mapDigest(target)) << "trial " << i;
		ASSERT_TRUE(d == oldDigest || d == newDigest)
		    << "trial " << i << ": a mixture of the two maps";
		(d == oldDigest ? keptOld : gotNew)++;
		if (kVerbose)
			std::printf(
			    "trial %d: kill %.1f ms after %s, status %d: %s map\n", i,
			    at * 1000, i % 4 ? "the save began" : "the start", status,
			    d == oldDigest ? "old" : "new");
	}
	std::printf(
	    "semnav-map: %d kills (%d while saving; saving took %.0f ms of %.0f): "
	    "%d left the old map, %d the new one, 0 a mixture\n",
	    trials, duringSave, saveSeconds * 1000, total * 1000, keptOld, gotNew);
	// A complete run cleans up what killed ones left beside the map.
	ASSERT_EQ(AppProcess("semnav-map", mapArgs(r.newRawlog, target)).wait(), 0);
	EXPECT_EQ(mapDigest(target), newDigest);
	EXPECT_EQ(hiddenEntries(root), 0u);
	fs::remove_all(root);
	fs::remove_all(r.dir);
}

TEST(AtomicOutputs, KilledSemnavSimLeavesAWholeDatasetOrARefusedOne)
{
	const fs::path root = tmpDir("sim");
	const std::vector<std::string> poses = {
	    "[1.5, 1.5, 0]", "[2.8, 3.9, 0]", "[5.5, 4.5, 0]"};
	const auto oldScene = writeScene(root, "tiny", {poses[0], poses[1]});
	// Every label image differs: the new run visits the stops backwards.
	const auto newScene =
	    writeScene(root, "tiny", {poses[2], poses[1], poses[0]});
	const auto simArgs = [](const fs::path& scene, const fs::path& out)
	{
		return std::vector<std::string>{"--scene",    scene.string(), "--out",
		                                out.string(), "--seed",       "1"};
	};
	ASSERT_EQ(
	    AppProcess("semnav-sim", simArgs(oldScene, root / "old")).wait(), 0);
	const fs::path out = root / "out";
	fs::copy(root / "old", out, fs::copy_options::recursive);
	AppProcess full("semnav-sim", simArgs(newScene, out));
	ASSERT_EQ(full.wait(), 0);
	const double total = full.elapsed();
	// Stale label images of a longer old run would be left in place by
	// file-by-file writing: the new dataset has exactly its own.
	fs::rename(out, root / "new");
	const uint64_t oldDigest = datasetDigest(root / "old", "tiny"),
	               newDigest = datasetDigest(root / "new", "tiny");
	ASSERT_NE(oldDigest, newDigest);

	std::mt19937 rng(static_cast<unsigned>(envInt("SEMNAV_KILL_SEED", 1)));
	const int trials = envInt("SEMNAV_KILL_TRIALS", 8);
	int keptOld = 0, gotNew = 0, refused = 0;
	for (int i = 0; i < trials; i++)
	{
		fs::remove_all(out);
		fs::copy(root / "old", out, fs::copy_options::recursive);
		AppProcess p("semnav-sim", simArgs(newScene, out));
		// Half the kills anywhere, half once the files are being replaced.
		if (i % 2 == 0)
			p.sleepThenKill(
			    std::uniform_real_distribution<double>(0, total * 1.05)(rng));
		else
		{
			p.waitFor(DatasetCompletion::markerPath(out.string(), "tiny"));
			p.sleepThenKill(
			    std::uniform_real_distribution<double>(0, 0.003)(rng));
		}
		p.wait();
		try
		{
			GroundTruthLog::forRawlog(out.string(), "tiny.rawlog");
			PerceptionRun::findLabelsDir(out.string(), "tiny");
		}
		catch (const IoError& e)
		{
			const std::string m = e.what();
			EXPECT_NE(m.find("incomplete"), std::string::npos) << m;
			EXPECT_EQ(m.find('\n'), std::string::npos) << m;
			refused++;
			continue;
		}
		const uint64_t d = datasetDigest(out, "tiny");
		ASSERT_TRUE(d == oldDigest || d == newDigest)
		    << "trial " << i << ": a mixture of the two datasets";
		(d == oldDigest ? keptOld : gotNew)++;
	}
	std::printf(
	    "semnav-sim: %d kills: %d left the old dataset, %d the new one, %d "
	    "one refused as incomplete, 0 a mixture\n",
	    trials, keptOld, gotNew, refused);
	fs::remove_all(root);
}

TEST(AtomicOutputs, SemnavNavLeavesNoNavlogDirectoryWhenItFails)
{
	const fs::path root = tmpDir("nav");
	const std::string scene = test::kSourceDir + "/datasets/nav/utrap.yaml";
	const auto navArgs = [&](const std::string& command, const fs::path& out)
	{
		return std::vector<std::string>{
		    "--gt-map",  scene,       "--scene", scene,   "--start",
		    "6.2,2.6,0", "--command", command,   "--out", out.string()};
	};
	// Failing before and after the log is opened, and terminated mid-run.
	EXPECT_NE(
	    AppProcess("semnav-nav", navArgs("go to 100 100", root / "a")).wait(),
	    0);
	for (const int sig : {SIGTERM, SIGINT, SIGHUP})
	{
		const fs::path out = root / ("sig" + std::to_string(sig));
		AppProcess p(
		    "semnav-nav", navArgs("go to the nearest wastebasket", out));
		const fs::path navlog = out / (".navlog-" + std::to_string(p.pid()));
		ASSERT_TRUE(p.waitFor(navlog)) << "no navlog directory to remove";
		std::this_thread::sleep_for(std::chrono::milliseconds(100));
		::kill(p.pid(), sig);
		EXPECT_EQ(p.wait(), -sig);
		EXPECT_FALSE(fs::exists(navlog)) << "signal " << sig;
	}
	for (const auto& e : fs::recursive_directory_iterator(root))
		EXPECT_EQ(
		    e.path().filename().string().rfind(".navlog-", 0),
		    std::string::npos)
		    << e.path();
	fs::remove_all(root);
}
