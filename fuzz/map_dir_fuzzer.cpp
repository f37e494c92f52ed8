/* semnav: semantic navigation from tilting-laser sweeps */
// libFuzzer harness: one file of a map directory through MapIO::load. A
// small map is saved once; the first input byte picks which of its files
// (map.yaml, a PNG, a PFM layer, octomap.bt) the rest of the input
// replaces, and the file is restored after the load.
#include <semnav/common/Error.h>
#include <semnav/map/MapIO.h>
#include <semnav/map/SemanticMap.h>

#include <algorithm>
#include <vector>

#include "../tests/map/MapTestUtils.h"
#include "FuzzFiles.h"

using namespace semnav;
namespace fs = std::filesystem;

namespace
{
/** Two sweeps of a floor fan with a box and a wastebasket detection. */
void buildMap(SemanticMap& m)
{
	auto pts = test::floorFan(2.0, 0.08);
	for (double y = -0.3; y <= 0.3; y += 0.04)
		pts.push_back({1.5, y, 0.3, Label::Obstacle});
	auto f = test::makeFakeSweep(pts);
	Detection d;
	d.label = Label::Wastebasket;
	d.imageBox = cv::Rect(0, 0, 3, 1);
	d.centroid = {1.2, 0.5, 0.2};
	d.extent = {0.3, 0.3, 0.4};
	d.shapeScore = 0.75;
	f.labeled.detections = {d};
	m.insert(f.sweep, f.labeled, mrpt::poses::CPose2D(1, 1, 0.3));
	m.insert(f.sweep, f.labeled, mrpt::poses::CPose2D(1.2, 1, 0.35));
}

struct Fixture
{
	fs::path base, work;
	std::vector<std::string> files;  ///< relative paths, sorted
};

Fixture makeFixture()
{
	Fixture f;
	const fs::path dir = fuzz::scratchDir("map_dir");
	f.base = dir / "base";
	f.work = dir / "work";
	fs::remove_all(f.base);
	fs::remove_all(f.work);
	SemanticMap m;
	buildMap(m);
	MapIO::save(m, f.base.string());
	fs::copy(f.base, f.work, fs::copy_options::recursive);
	for (const auto& e : fs::recursive_directory_iterator(f.base))
		if (e.is_regular_file())
			f.files.push_back(fs::relative(e.path(), f.base).string());
	std::sort(f.files.begin(), f.files.end());
	for (std::size_t i = 0; i < f.files.size(); i++)
	{
		std::string name = f.files[i];
		std::replace(name.begin(), name.end(), '/', '_');
		fuzz::writeSeed(name, char(i) + fuzz::readBytes(f.base / f.files[i]));
	}
	return f;
}

const Fixture& fixture()
{
	static const Fixture f = makeFixture();
	return f;
}
}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
	fixture();
	return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
	if (size == 0) return 0;
	const Fixture& f = fixture();
	const std::string& file = f.files[data[0] % f.files.size()];
	fuzz::writeBytes(f.work / file, data + 1, size - 1);
	try
	{
		SemanticMap m;
		MapIO::load(f.work.string(), m);
	}
	catch (const Error&)
	{
	}
	fs::copy_file(
	    f.base / file, f.work / file, fs::copy_options::overwrite_existing);
	return 0;
}
