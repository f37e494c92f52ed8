/* semnav: semantic navigation from tilting-laser sweeps */
// DetectionEvaluation::recognisableViews() counts doors too (the map's
// objects, scored by scripts/eval-generated --map): on a generated building
// (tuning seed 0) a door's recognisable views are its views with >= 150
// pixels less those beside the robot or seen over less than half their
// height, so some views are left out and none is added.
#include <gtest/gtest.h>
#include <semnav/sim/SceneGenerator.h>
#include <semnav/sim/SceneLoader.h>
#include <semnav/sim/SimulationRunner.h>
#include <semnav/training/DetectionEvaluation.h>
#include <semnav/training/SimDataset.h>
#include <unistd.h>

#include <filesystem>
#include <map>
#include <string>

#include "../TestPaths.h"

using namespace semnav;
namespace fs = std::filesystem;

TEST(DetectionEvaluation, CountsADoorsRecognisableViews)
{
	SceneGenerator::TOptions gen;
	gen.seed = 0;
	const Scene scene =
	    SceneLoader::parse(SceneGenerator(gen).generate(), "indoor_0");
	const fs::path dir = fs::temp_directory_path() /
	                     ("semnav_doorviews_" + std::to_string(::getpid()));
	fs::remove_all(dir);
	SimulationRunner(scene, SimulationRunner::TOptions(), 0).run(dir.string());

	DetectionEvaluation ev(CascadeDetector::TOptions::fromIniFile(
	    test::kSourceDir + "/config/cascade.ini"));
	std::map<int, std::size_t> pixelViews;  // door id -> sweeps >= 150 px
	for (const auto& s : SimDataset::load(dir.string()))
	{
		ev.add(s);
		for (const auto& g :
		     GroundTruthObject::fromLabelImage(s.groundTruth, {Label::Door}))
			if (g.pixels >= DetectionEvaluation::kCountedPixels)
				pixelViews[g.instance]++;
	}
	fs::remove_all(dir);

	std::size_t doors = 0, byPixels = 0, recognisable = 0;
	for (const auto& o : scene.objects)
	{
		if (o.label != Label::Door) continue;
		doors++;
		const auto it = ev.recognisableViews().find(o.id);
		const std::size_t views =
		    it == ev.recognisableViews().end() ? 0 : it->second;
		EXPECT_LE(views, pixelViews[o.id]) << "door " << o.id;
		byPixels += pixelViews[o.id];
		recognisable += views;
	}
	ASSERT_GT(doors, 0u);
	EXPECT_GT(recognisable, 0u);
	// Measured: 13 recognisable of 16 views with >= 150 pixels.
	EXPECT_LT(recognisable, byPixels);
}
