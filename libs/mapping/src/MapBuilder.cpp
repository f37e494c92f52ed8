/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/CommandLine.h>
#include <semnav/common/Error.h>
#include <semnav/mapping/MapBuilder.h>
#include <semnav/scan/RawlogSweepReader.h>
#include <semnav/scan/ThreeDtkReader.h>

#include <chrono>
#include <filesystem>
#include <iostream>

namespace semnav
{
std::string MapBuilder::poseSourceName(PoseSource p)
{
	switch (p)
	{
		case PoseSource::Odometry:
			return "odometry";
		case PoseSource::GroundTruth:
			return "gt";
		case PoseSource::Localization:
			return "pf";
	}
	return "";
}

std::optional<MapBuilder::PoseSource> MapBuilder::poseSourceFromName(
    const std::string& s)
{
	for (PoseSource p :
	     {PoseSource::Odometry, PoseSource::GroundTruth,
	      PoseSource::Localization})
		if (poseSourceName(p) == s) return p;
	return std::nullopt;
}

MapBuilder::MapBuilder(const Settings& settings)
    : m_settings(settings),
      m_perception(settings.perception, settings.cascades),
      m_map(settings.map)
{
	const std::string& rawlog = m_settings.rawlog;
	if (!m_settings.gtDir.empty())
		m_gt = GroundTruthLog::forRawlog(m_settings.gtDir, rawlog);
	else if (m_settings.poses == PoseSource::GroundTruth && !rawlog.empty())
		m_gt = GroundTruthLog::forRawlog(
		    std::filesystem::path(rawlog).parent_path().string(), rawlog);
	if (m_settings.poses == PoseSource::GroundTruth && !m_gt)
		throw Error("--poses gt needs a rawlog from semnav-sim (or --gt-dir)");
	// A 3DTK scan without its pose would land at the origin, on top of the
	// others: refuse (docs/mapping.md, "The real 3DTK scans").
	for (const auto& scan : m_settings.scans3dtk)
		if (const auto pose = ThreeDtkReader::posePath(scan);
		    !std::filesystem::exists(pose))
			throw IoError(
			    scan + ": no pose file " + pose +
			    " (each 3DTK scan is placed by its .pose; for the map origin "
			    "write '0 0 0' and '0 0 0' into it)");
	if (!rawlog.empty())
		m_reader =
		    std::make_unique<RawlogSweepReader>(rawlog, m_settings.assembler);
	if (m_settings.poses == PoseSource::Localization)
		m_localizer =
		    std::make_unique<MappingLocalizer>(m_settings.localization);
}

MapBuilder::~MapBuilder() = default;

std::size_t MapBuilder::expectedSweeps() const
{
	return m_gt ? m_gt->size() : 0;
}

std::size_t MapBuilder::sweepsDroppedMoving() const
{
	return m_reader ? m_reader->assembler().sweepsDroppedMoving() : 0;
}

bool MapBuilder::nextSweep(Sweep& sweep)
{
	while (m_reader)
	{
		if (!m_reader->next(sweep)) return false;
		if (sweep.quality().complete) return true;
		m_skippedIncomplete++;
		std::cerr << "MapBuilder: sweep " << sweep.index()
		          << " skipped: incomplete (" << sweep.rows() << " rows)\n";
	}
	if (m_next3dtk == m_settings.scans3dtk.size()) return false;
	sweep = ThreeDtkReader().read(m_settings.scans3dtk[m_next3dtk]);
	sweep.setIndex(m_next3dtk++);
	return true;
}

mrpt::poses::CPose2D MapBuilder::insert(
    const Sweep& sweep, const LabeledSweep& ls)
{
	mrpt::poses::CPose2D pose = sweep.odometry();
	if (m_settings.poses == PoseSource::GroundTruth)
		pose = m_gt->pose(sweep.index());
	if (m_localizer)
	{
		pose = m_localizer->process(sweep, ls, m_map);
		if (m_map.sweepsInserted() > 1)
		{
			m_locMs.push_back(m_localizer->lastUpdate().ms);
			m_updates.push_back(m_localizer->lastUpdate());
		}
	}
	else
		m_map.insert(sweep, ls, pose);
	return pose;
}

void MapBuilder::run(const std::function<void(std::size_t)>& progress)
{
	Sweep sweep;
	for (;;)
	{
		try
		{
			if (!nextSweep(sweep)) break;
		}
		catch (const RawlogError& e)
		{
			m_readError = e.what();  // keep the map of the good sweeps
			break;
		}
		const auto t0 = std::chrono::steady_clock::now();
		LabeledSweep ls;
		try
		{
			ls = m_perception.process(sweep);
		}
		catch (const std::exception& e)
		{
			// One odd sweep (what a fault left) must not end the run.
			m_failed++;
			std::cerr << "MapBuilder: sweep " << sweep.index() << " ("
			          << sweep.rows() << " x " << sweep.cols()
			          << ") skipped: " << CommandLine::firstLine(e.what())
			          << "\n";
			continue;
		}
		const mrpt::poses::CPose2D pose = insert(sweep, ls);
		if (scored())
		{
			const auto& truth = m_gt->pose(sweep.index());
			m_poseError.add(pose, truth);
			m_odometryError.add(sweep.odometry(), truth);
		}
		m_ms.push_back(std::chrono::duration<double, std::milli>(
		                   std::chrono::steady_clock::now() - t0)
		                   .count());
		if (scored())
			m_scorer.add(
			    ls.labels,
			    GroundTruthScorer::readLabelImage(
			        m_gt->labelImagePath(sweep.index())),
			    ls.validMask);
		if (progress) progress(m_ms.size());
	}
}
}  // namespace semnav
