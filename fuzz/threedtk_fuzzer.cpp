/* semnav: semantic navigation from tilting-laser sweeps */
// libFuzzer harness: a 3DTK scan through ThreeDtkReader::read and the same
// bytes as a .pose through ThreeDtkReader::readPose. The first byte sets the
// beams per line (1..16) so small inputs reach the whole reader.
#include <semnav/common/Error.h>
#include <semnav/scan/ThreeDtkReader.h>

#include <cmath>
#include <sstream>

#include "FuzzFiles.h"

using namespace semnav;

namespace
{
/** `rows` lines of `cols` points of a wall 3 m ahead, tilting up. */
std::string syntheticScan(int rows, int cols)
{
	std::ostringstream s;
	for (int r = 0; r < rows; r++)
		for (int c = 0; c < cols; c++)
		{
			const double phi = (-90 + 180.0 * c / cols) * M_PI / 180;
			const double theta = (-10 + 2.0 * r) * M_PI / 180;
			const double range = c == 2 ? 0 : 300.0;  // cm; one no-return
			s << range * std::sin(phi) << ' ' << range * std::sin(theta) << ' '
			  << range * std::cos(phi) * std::cos(theta) << '\n';
		}
	return s.str();
}

void writeSeeds()
{
	fuzz::writeSeed("wall", char(7) + syntheticScan(6, 8));
	fuzz::writeSeed("wall-one-line", char(3) + syntheticScan(1, 4));
	fuzz::writeSeed("pose", char(0) + std::string("120.5 0 -33.25\n0 45 0\n"));
}
}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
	writeSeeds();
	return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
	if (size == 0) return 0;
	static const auto dir = fuzz::scratchDir("threedtk");
	ThreeDtkReader::TOptions o;
	o.cols = 1 + data[0] % 16;
	fuzz::writeBytes(dir / "scan000.3d", data + 1, size - 1);
	fuzz::writeBytes(dir / "scan000.pose", data + 1, size - 1);
	try
	{
		ThreeDtkReader(o).read((dir / "scan000.3d").string());
	}
	catch (const Error&)
	{
	}
	try
	{
		ThreeDtkReader::readPose((dir / "scan000.pose").string());
	}
	catch (const Error&)
	{
	}
	return 0;
}
