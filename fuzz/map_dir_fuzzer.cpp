/* semnav: semantic navigation from tilting-laser sweeps */
// libFuzzer harness: one file of a map directory through MapIO::load. A
// small map is saved once; the first input byte picks which of its files
// (map.yaml, a PNG, a PFM layer, octomap.bt) the rest of the input
// replaces, and the file is restored after the load.
#include <semnav/common/Error.h>
#include <semnav/map/MapIO.h>
#include <semnav/map/SemanticMap.h>
#include <semnav/perception/LabeledSweep.h>
#include <semnav/scan/TiltGeometry.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "FuzzFiles.h"

using namespace semnav;
namespace fs = std::filesystem;

namespace
{
/** Two sweeps of a floor fan with a box and a wastebasket detection. */
void buildMap(SemanticMap& m)
{
	std::vector<std::pair<cv::Vec3f, Label>> pts;
	for (double a = -0.6; a <= 0.6; a += 0.05)
		for (double r = 0.3; r <= 2.0; r += 0.08)
			pts.push_back(
			    {cv::Vec3f(r * std::cos(a), r * std::sin(a), 0), Label::Floor});
	for (double y = -0.3; y <= 0.3; y += 0.04)
		pts.push_back({cv::Vec3f(1.5, y, 0.3), Label::Obstacle});
	const int n = static_cast<int>(pts.size());
	Sweep sweep(1, pts.size());
	sweep.setRow(0, 0.0, tiltedSensorPose({0, 0, 0.45}, 0.0));
	LabeledSweep ls;
	ls.labels = cv::Mat(1, n, CV_8U, cv::Scalar(0));
	ls.validMask = cv::Mat(1, n, CV_8U, cv::Scalar(1));
	ls.points = cv::Mat(1, n, CV_32FC3);
	ls.regionIds = cv::Mat(1, n, CV_32S, cv::Scalar(-1));
	ls.roughnessBar = cv::Mat(1, n, CV_32F, cv::Scalar(1.0f));
	for (int i = 0; i < n; i++)
	{
		ls.points.at<cv::Vec3f>(0, i) = pts[i].first;
		ls.labels.at<uint8_t>(0, i) = static_cast<uint8_t>(pts[i].second);
	}
	Detection d;
	d.label = Label::Wastebasket;
	d.imageBox = cv::Rect(0, 0, 3, 1);
	d.centroid = {1.2, 0.5, 0.2};
	d.extent = {0.3, 0.3, 0.4};
	d.shapeScore = 0.75;
	ls.detections = {d};
	m.insert(sweep, ls, mrpt::poses::CPose2D(1, 1, 0.3));
	m.insert(sweep, ls, mrpt::poses::CPose2D(1.2, 1, 0.35));
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
