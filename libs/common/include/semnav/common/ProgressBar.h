/* semnav: semantic navigation from tilting-laser sweeps */
#pragma once

#include <cstddef>
#include <string>

namespace semnav
{
/** A one-line progress bar on stderr, drawn only when stderr is a terminal
 * (so logs and --json output stay clean). */
class ProgressBar
{
public:
	/** total = 0: the total is unknown, a counter is shown. */
	ProgressBar(std::size_t total, std::string what);
	~ProgressBar();

	/** Sets the number of finished items and redraws. */
	void update(std::size_t done);
	/** Ends the bar with a newline (also done by the destructor). */
	void finish();

	bool enabled() const { return m_enabled; }

private:
	std::size_t m_total;
	std::string m_what;
	bool m_enabled;
	bool m_finished = false;
};

}  // namespace semnav
