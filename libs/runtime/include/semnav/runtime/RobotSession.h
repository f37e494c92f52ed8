/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/math/TPose2D.h>
#include <mrpt/system/COutputLogger.h>
#include <semnav/nav/NavLogFile.h>
#include <semnav/nav/NavigationConfig.h>
#include <semnav/nav/NavigationLoop.h>
#include <semnav/nav/SemanticNavigator.h>
#include <semnav/nav/StopAndScanLocalizer.h>
#include <semnav/robot/RobotInterfaces.h>
#include <semnav/robot/SweepObstacles.h>
#include <semnav/runtime/RobotSessionObserver.h>

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace semnav
{
class CommandQueue;
class SemanticMap;

/** One run of semnav on a robot (semnav-robot): it localizes the robot in
 * its map, then takes operator commands one line at a time ("go to the
 * nearest <label>", "go to <label> <id>", "go to <x> <y>", "stop",
 * "status", "save map") and drives them with the runtime's NavigationLoop
 * (SemanticNavigator + StopAndScanLocalizer), exactly as in the simulator.
 *
 * - **The map grows**: every sweep the localizer takes with a converged,
 *   consistent estimate is inserted into the map at that estimate (walls,
 *   labels, objects first seen become instances, as semnav-map does); the
 *   localizer and the navigator then work on the new map.
 * - **No map at all** (an empty map, nothing inserted): the robot maps as
 *   semnav-map --poses pf does (MappingLocalizer: every stop-and-scan sweep
 *   is localized against the map built so far, then inserted; the first
 *   one at the odometry origin), and the planner crosses never-observed
 *   cells at explore_u_unobserved when [Traversability] u_unobserved
 *   blocks them: the plan through unseen space is optimistic, each sweep
 *   shows walls and the navigator replans.
 * - **Safety**: while driving, a laser that has sent no scan line for
 *   laser_silence_s, or odometry older than odometry_timeout_s, stops the
 *   base and pauses the navigation until they return (odometry gone for
 *   odometry_lost_s fails the command). A stop request (SIGINT/SIGTERM)
 *   stops the base first.
 * - **Progress**: every event is one JSON object for the event sink (state,
 *   pose, goal, sweeps, objects, replans); bad commands get a one-line
 *   error and the robot keeps doing what it was doing.
 *
 * Options: INI section [SemnavRobot] (config/robot.ini). */
class RobotSession : public mrpt::system::COutputLogger
{
public:
	struct TOptions : public mrpt::config::CLoadableOptions
	{
		void loadFromConfigFile(
		    const mrpt::config::CConfigFileBase& c,
		    const std::string& section) override;
		void saveToConfigFile(
		    mrpt::config::CConfigFileBase& c,
		    const std::string& section) const override;

		/** localize: how the robot finds itself in a map at the start:
		 * global (anywhere) or tracking (around start_pose). */
		StopAndScanLocalizer::Mode localize =
		    StopAndScanLocalizer::Mode::Global;
		/** start_pose: "x y yaw_deg" for a tracking start. */
		std::vector<double> startPose;
		/** grow_map: insert the localized sweeps into the map. */
		bool growMap = true;
		/** laser_silence_s: no scan line for this long while driving
		 * stops the base until lines return. */
		double laserSilence = 0.3;
		/** odometry_timeout_s, odometry_lost_s: odometry older than the
		 * first pauses the navigation; older than the second fails the
		 * command. */
		double odometryTimeout = 0.3;
		double odometryLost = 5.0;
		/** command_time_limit_s: a command still running after this long
		 * is cancelled. */
		double commandTimeLimit = 900;
		/** status_period_s: a status event this often while driving (0:
		 * only on request). */
		double statusPeriod = 0;
		/** explore_u_unobserved: u of never-observed cells for a run that
		 * starts with no map while [Traversability] u_unobserved blocks
		 * them (a value >= L keeps them blocked). */
		double exploreUnobserved = 0.2;
		/** unseen_rescan_m, unseen_lookahead_m: starting with no map, a
		 * sweep as soon as the robot has driven unseen_rescan_m since the
		 * last one while its path, within unseen_lookahead_m ahead, passes
		 * within the robot's radius of a never-observed cell (0: only every
		 * rescan_distance_m). */
		double unseenRescan = 0.3;
		double unseenLookahead = 0.8;
	};

	/** What the session reports (one JSON object per event). */
	using EventSink = std::function<void(const nlohmann::json&)>;
	/** Scan lines received so far (a live sensor's counter): the laser's
	 * pulse. Empty: not monitored. */
	using LineCounter = std::function<std::size_t()>;

	/** `robot` gives base, sweeps, clock and the pose to report (a
	 * LocalizedPose); `obstacles` takes every sweep. All must outlive the
	 * session. */
	RobotSession(
	    SemanticMap& map, const RobotInterfaces& robot,
	    SweepObstacles& obstacles, const NavigationConfig& navigation,
	    const MappingLocalizer::TOptions& localization,
	    const PerceptionPipeline::TOptions& perception,
	    const std::optional<CascadeDetector::TOptions>& cascades,
	    const TOptions& options, EventSink events);
	~RobotSession() override;

	/** Watches the laser's scan lines (laser_silence_s). */
	void monitorLaser(LineCounter lines) { m_lines = std::move(lines); }
	/** MRPT's navigation log of every command (navlog-viewer) goes to
	 * `path`, written by finishNavLog(). */
	void setNavLogPath(const std::string& path) { m_navlogPath = path; }
	/** Closes the navigation log and moves it in place ("" for none). */
	std::string finishNavLog();
	/** `o` sees the map, plans, pose and sweeps from now on (it must
	 * outlive the session). */
	void addObserver(RobotSessionObserver& o)
	{
		m_observers.push_back({&o, std::nullopt});
	}
	/** Called on "save map" and by finish(). */
	void onSaveMap(std::function<void()> save) { m_save = std::move(save); }

	/** Localizes the robot (start of the run). False (an event says why)
	 * when it could not; commands are refused until a later start works. */
	bool localize();
	/** Takes commands from `queue` until it is closed and empty or `stop`
	 * is set; then stops the base. */
	void run(CommandQueue& queue, const std::atomic<bool>& stop);

	/** One command line (also used by run()); false for a bad one (an
	 * error event names it). A "go to" drives until done. */
	bool handle(const std::string& line, const std::atomic<bool>& stop);

	/** The state as a JSON object (the "status" event). */
	nlohmann::json status() const;
	/** Counters. */
	int sweepsInserted() const { return m_inserted; }
	int commandsDone() const { return m_done; }
	int commandErrors() const { return m_errors; }
	/** Every plan of every command (map frame), for the run's picture. */
	const std::vector<SemanticNavigator::PlanRecord>& plans() const
	{
		return m_plans;
	}
	/** The believed trajectory (one pose per control period). */
	const std::vector<mrpt::math::TPose2D>& trajectory() const
	{
		return m_trajectory;
	}
	/** The last command's navigator (nullptr before the first). */
	const SemanticNavigator* navigator() const { return m_nav.get(); }
	/** The run started with no map: it maps as semnav-map --poses pf. */
	bool mapping() const { return m_mapping; }
	/** The navigation configuration in use (u_unobserved may be the
	 * explore value). */
	const NavigationConfig& config() const { return m_config; }

private:
	struct Driving;
	/** [x, y, yaw_deg]. */
	static nlohmann::json poseJson(const mrpt::math::TPose2D& p);
	void emit(nlohmann::json e) const;
	/** The observers' map (when changed), plan (when new) and pose. */
	void notifyObservers();
	void notifySweep(
	    const Sweep& sweep, const LabeledSweep& labeled,
	    const mrpt::math::TPose2D& estimate, double stdXY, double stdYaw);
	void error(const std::string& line, const std::string& why);
	/** Parses and checks a "go to" command against the map from the
	 * current pose (growing the grid to hold a point goal beyond it);
	 * throws NavigationError/PlanningError naming it. */
	NavCommand checkedGoal(const std::string& line);
	/** Drives `command` until it ends (or is replaced or stopped). */
	void drive(const NavCommand& command, const std::atomic<bool>& stop);
	/** The started command's NavigationLoop (with no starting map, the
	 * arrival checks by mapping sweeps too); fills `done`'s counters.
	 * Throws LocalizationFailedError. */
	void runLoop(
	    Driving& d, const std::atomic<bool>& stop, nlohmann::json& done);
	/** Every control period while driving: sweeps into the map, safety,
	 * commands. */
	void whileDriving(
	    SemanticNavigator& nav, Driving& d, const std::atomic<bool>& stop);
	/** Inserts the localizer's kept sweeps; true when the map changed. */
	bool insertSweeps();
	/** A "new_object" event for every reported instance not known yet. */
	void reportNewObjects();
	/** Blocks with the base stopped while the laser is silent or the
	 * odometry stale; returns why the command must end (odometry or laser
	 * lost), "" to go on. */
	std::string waitForSensors(const std::atomic<bool>& stop);
	double laserSilence();
	double odometryAge() const;
	/** A localizer on the map (the map must have walls). */
	void makeLocalizer();
	/** Mapping (an empty start): stops, sweeps, localizes the sweep
	 * against the map so far and inserts it (MappingLocalizer; the first
	 * sweep goes in at the odometry pose, which makes the odometry frame
	 * the map frame); the robot reports the estimate. */
	void mappingSweep();
	/** Mapping, while driving: a mapping sweep every rescan_distance_m of
	 * odometry, or earlier before the path enters never-observed cells
	 * (unseen_rescan_m); true when one was taken. */
	bool mappingRescan(const SemanticNavigator& nav);
	/** The navigator's path, within unseen_lookahead_m ahead of the
	 * robot, passes within the robot's radius of a never-observed cell. */
	bool pathAheadUnseen(const SemanticNavigator& nav) const;
	/** Mapping, at a believed arrival: one sweep, then a replan from the
	 * corrected pose; true when that pose is in the goal region. */
	bool confirmArrivalByMapping(SemanticNavigator& nav);
	CommandQueue* m_queue = nullptr;

	SemanticMap& m_map;
	RobotInterfaces m_robot;
	SweepObstacles& m_obstacles;
	NavigationConfig m_config;
	TOptions m_options;
	EventSink m_events;
	MappingLocalizer::TOptions m_localization;
	PerceptionPipeline::TOptions m_perception;
	std::optional<CascadeDetector::TOptions> m_cascades;
	LineCounter m_lines;
	std::function<void()> m_save;
	std::unique_ptr<StopAndScanLocalizer> m_localizer;
	/** Mapping (empty start): the localizer and perception of each sweep,
	 * and the odometry distance at the last sweep. */
	bool m_mapping = false;
	std::unique_ptr<MappingLocalizer> m_mapper;
	std::unique_ptr<SweepPerception> m_mapperPerception;
	double m_lastMappingSweepAt = 0;
	std::unique_ptr<class RobotNavInterface> m_interface;
	std::unique_ptr<SemanticNavigator> m_nav;
	std::string m_navlogPath;
	std::unique_ptr<NavLogFile> m_navlog;
	bool m_localized = false;
	int m_inserted = 0, m_done = 0, m_errors = 0, m_sweeps = 0;
	std::size_t m_lastLines = 0;
	double m_lastLineTime = 0;
	std::optional<NavCommand> m_current, m_next;
	/** Reported instances already announced. */
	std::set<int> m_known;
	std::vector<SemanticNavigator::PlanRecord> m_plans;
	std::vector<mrpt::math::TPose2D> m_trajectory;
	struct Observer
	{
		RobotSessionObserver* observer;
		/** The map version it accepted last. */
		std::optional<std::uint64_t> mapVersion;
	};
	std::vector<Observer> m_observers;
	/** Plans of the running command the observers have seen. */
	std::size_t m_observedPlans = 0;
};

}  // namespace semnav
