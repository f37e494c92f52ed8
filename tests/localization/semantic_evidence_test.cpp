/* semnav: semantic navigation from tilting-laser sweeps */
// SemanticEvidenceMap: a sweep's labels and objects score higher where they
// agree with the map; a room and its half-turned twin are told apart by a
// wastebasket on one side; each term can be turned off; options are checked.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <semnav/common/Error.h>
#include <semnav/common/LabelSet.h>
#include <semnav/localization/SemanticEvidenceMap.h>
#include <semnav/map/SemanticMap.h>

#include <cmath>

using namespace semnav;

namespace
{
/** Fills `map` with a 6 x 4 m room: floor everywhere, a door cell strip on the
 * west wall at y 1.5..2.5, a wastebasket instance at (3, 3.5). All cells
 * observed. */
void buildRoom(SemanticMap& map)
{
	map.growToInclude(0, 0, 6, 4);
	const GridGeometry& g = map.geometry();
	auto& labels = map.get("labels");
	auto& seen = map.get("observations");
	for (int cy = 0; cy < g.rows; cy++)
		for (int cx = 0; cx < g.cols; cx++)
		{
			const double x = g.centerX(cx), y = g.centerY(cy);
			if (x < 0 || y < 0 || x > 6 || y > 4) continue;
			LabelSet ls;
			if (x < 0.1 && y > 1.5 && y < 2.5)
				ls.insert(Label::Door);
			else if (std::hypot(x - 3, y - 3.5) < 0.15)
				ls.insert(Label::Wastebasket);
			else
				ls.insert(Label::Floor);
			labels[g.index(cy, cx)] = static_cast<float>(ls.mask());
			seen[g.index(cy, cx)] = 1;
		}
	map.addInstance(Label::Wastebasket, {2.85, 3.35, 0}, {3.15, 3.65, 0.4}, 5);
}

/** What the robot at (1.5, 1.2, 0) sees: the wastebasket at (1.5, 2.3) in
 * its frame, its points, the floor around and the door strip. */
SemanticObservation seenFromStart()
{
	SemanticObservation o;
	o.objects.push_back({1.5f, 2.3f, Label::Wastebasket});
	o.classSamples.push_back({1.5f, 2.3f, Label::Wastebasket});
	for (float y = 0.4f; y < 1.3f; y += 0.2f)
		o.classSamples.push_back({-1.45f, y, Label::Door});
	for (float x = -1.0f; x <= 3.0f; x += 0.5f)
		for (float y = -1.0f; y <= 2.0f; y += 0.5f)
			o.groundSamples.push_back({x, y, Label::Floor});
	return o;
}
}  // namespace

TEST(SemanticEvidence, TheTruePoseBeatsTheTwin)
{
	SemanticMap map;
	buildRoom(map);
	SemanticEvidenceMap ev;
	ev.build(map);
	ASSERT_TRUE(ev.hasField(Label::Door));
	ASSERT_TRUE(ev.hasField(Label::Floor));
	EXPECT_FALSE(ev.hasField(Label::Stairs));
	const SemanticObservation obs = seenFromStart();
	const auto truth = ev.terms(1.5, 1.2, 0, obs);
	// The room turned by half a turn about its centre (3, 2).
	const auto twin = ev.terms(4.5, 2.8, M_PI, obs);
	EXPECT_GT(truth.objects, twin.objects + 1.0);
	EXPECT_GT(truth.classes, twin.classes + 1.0);
	// The floor is everywhere: the ground term cannot tell them apart.
	EXPECT_NEAR(truth.ground, twin.ground, 0.2);
	EXPECT_GT(
	    ev.logLikelihood(1.5, 1.2, 0, obs),
	    ev.logLikelihood(4.5, 2.8, M_PI, obs));
	// A pose 30 cm off scores lower than the truth, higher than the twin.
	const double off = ev.logLikelihood(1.8, 1.2, 0, obs);
	EXPECT_LT(off, truth.total());
	EXPECT_GT(off, twin.total());
}

TEST(SemanticEvidence, TermsTurnOffAndUnknownLabelsScoreAlike)
{
	SemanticMap map;
	buildRoom(map);
	SemanticEvidenceMap::TOptions o;
	o.objectPoints = 0;
	o.classPoints = 0;
	SemanticEvidenceMap ev(o);
	ev.build(map);
	const SemanticObservation obs = seenFromStart();
	const auto t = ev.terms(1.5, 1.2, 0, obs);
	EXPECT_EQ(t.objects, 0.0);
	EXPECT_EQ(t.classes, 0.0);
	// Floor seen where the map has floor fits; floor put outside the room
	// does not.
	EXPECT_GT(t.ground, ev.terms(5.8, 3.8, 0, obs).ground + 0.5);
	// Stairs the map does not hold: every pose alike (not scored).
	SemanticObservation stairs;
	stairs.classSamples.push_back({1, 1, Label::Stairs});
	SemanticEvidenceMap all;
	all.build(map);
	EXPECT_EQ(all.logLikelihood(1, 1, 0, stairs), 0.0);
	EXPECT_EQ(all.logLikelihood(4, 3, 2, stairs), 0.0);
}

TEST(SemanticEvidence, OptionsRejectUnknownKeysAndOutOfRange)
{
	const auto load = [](const std::string& text)
	{
		mrpt::config::CConfigFileMemory c(text);
		SemanticEvidenceMap::TOptions o;
		o.loadFromConfigFile(c, "SemanticEvidence");
		return o;
	};
	EXPECT_EQ(load("[SemanticEvidence]\nobject_points = 0\n").objectPoints, 0);
	EXPECT_FALSE(load("[SemanticEvidence]\nobject_points = 0\nclass_points = "
	                  "0\nground_points = 0\n")
	                 .enabled());
	EXPECT_THROW(load("[SemanticEvidence]\nobject_point = 1\n"), ConfigError);
	EXPECT_THROW(load("[SemanticEvidence]\nsigma_m = -1\n"), ConfigError);
}
