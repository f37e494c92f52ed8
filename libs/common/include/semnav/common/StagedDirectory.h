/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <functional>
#include <string>

namespace semnav
{
/** A directory replaced as a whole: the caller fills a sibling staging
 * directory (`.<name>.new-<pid>`), then commit() flushes it to disk and
 * swaps it with the target in one atomic renameat2(RENAME_EXCHANGE), so
 * that at every moment (a kill, a power cut) the target is the complete old
 * directory or the complete new one, never a mixture; the old one is then
 * removed. Where the file system cannot exchange, commit() marks the
 * staging directory complete (`.<name>.ready-<pid>`) and does two renames;
 * an interruption between them leaves no target, which interruptedSave()
 * names. Staging directories of dead processes are cleaned up (a complete
 * one becomes the target if there is none). Destroyed uncommitted, the
 * staging directory is removed. */
class StagedDirectory
{
public:
	/** Which names may sit in an existing target: commit() refuses to
	 * replace (and so delete) a directory holding anything else. */
	using OwnEntry = std::function<bool(const std::string& name)>;

	StagedDirectory(const std::string& target, OwnEntry ownEntry);
	~StagedDirectory();
	StagedDirectory(const StagedDirectory&) = delete;
	StagedDirectory& operator=(const StagedDirectory&) = delete;

	/** The staging directory to write into (exists, empty). */
	const std::string& path() const { return m_staged; }

	/** Swaps the staged directory in; throws IoError naming the target. */
	void commit();

	/** Throws IoError when `target` exists and is not a directory or holds
	 * an entry that is not `ownEntry`'s (what commit() refuses): for writers
	 * to check before long work. */
	static void checkReplaceable(
	    const std::string& target, const OwnEntry& ownEntry);

	/** A complete directory that an interrupted commit() left instead of
	 * `target` (which does not exist then), or "" when there is none. */
	static std::string interruptedSave(const std::string& target);

private:
	std::string m_target, m_staged;
	OwnEntry m_ownEntry;
	bool m_committed = false;
};

}  // namespace semnav
