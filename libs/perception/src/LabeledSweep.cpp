/* semnav: semantic navigation from tilting-laser sweeps */
#include <semnav/perception/LabeledSweep.h>

namespace semnav
{
std::size_t LabeledSweep::count(Label l) const
{
	const auto v = static_cast<uint8_t>(l);
	std::size_t n = 0;
	for (int r = 0; r < labels.rows; r++)
	{
		const uint8_t* L = labels.ptr<uint8_t>(r);
		for (int c = 0; c < labels.cols; c++) n += L[c] == v;
	}
	return n;
}

}  // namespace semnav
