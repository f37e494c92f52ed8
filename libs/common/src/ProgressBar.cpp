/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/common/ProgressBar.h>
#include <unistd.h>

#include <cstdio>

namespace semnav
{
ProgressBar::ProgressBar(std::size_t total, std::string what)
    : m_total(total), m_what(std::move(what)), m_enabled(::isatty(2) == 1)
{
}

ProgressBar::~ProgressBar()
{
	finish();
}

void ProgressBar::update(std::size_t done)
{
	if (!m_enabled || m_finished) return;
	if (m_total == 0)  // unknown total: a counter
	{
		std::fprintf(stderr, "\r%s: %zu", m_what.c_str(), done);
		std::fflush(stderr);
		return;
	}
	constexpr int kWidth = 40;
	const double f = m_total ? static_cast<double>(done) / m_total : 1.0;
	const int filled = static_cast<int>(f * kWidth + 0.5);
	std::fprintf(stderr, "\r%s [", m_what.c_str());
	for (int i = 0; i < kWidth; i++) std::fputc(i < filled ? '#' : '.', stderr);
	std::fprintf(stderr, "] %zu/%zu", done, m_total);
	std::fflush(stderr);
}

void ProgressBar::finish()
{
	if (m_enabled && !m_finished) std::fputc('\n', stderr);
	m_finished = true;
}

}  // namespace semnav
