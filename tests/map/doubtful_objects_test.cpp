/* semnav: semantic navigation from tilting-laser sweeps */
// Cascade objects whose shape check was not sure: the size and place rules
// of SemanticMap::doubtfulObjectReason() (docs/mapping.md, "Objects in
// the map").
#include <gtest/gtest.h>
#include <semnav/map/SemanticMap.h>

#include <functional>
#include <vector>

using namespace semnav;

namespace
{
/** An instance of `label` at (x, y), bottom 0.02 m, top `top`, detected in
 * every one of its views, one sighting per given width. */
ObjectInstance doubtful(
    Label label, double x, double y, double top,
    const std::vector<double>& widths, double shapeScore = 0.6)
{
	ObjectInstance o;
	o.label = label;
	o.centroid = {x, y, 0.5 * top};
	o.minCorner = {x - 0.2, y - 0.2, 0.02};
	o.maxCorner = {x + 0.2, y + 0.2, top};
	for (const double w : widths)
	{
		o.sightings.push_back(o.centroid);
		o.sightingSizes.push_back({w, 0, top - 0.02});
	}
	o.observations = widths.size();
	o.views = widths.size();
	o.bestShapeScore = shapeScore;
	return o;
}

/** `o` is not reported, but is when sure (shape score `sureScore`) or with
 * the rule turned off by `ruleOff`. */
void expectHeldBackOnlyWhileDoubtful(
    const ObjectInstance& o, double sureScore,
    const std::function<void(SemanticMap::TOptions&)>& ruleOff)
{
	EXPECT_FALSE(SemanticMap().reported(o));
	auto sure = o;
	sure.bestShapeScore = sureScore;
	EXPECT_TRUE(SemanticMap().reported(sure))
	    << "the rule is for doubtful ones";
	SemanticMap::TOptions opts;
	ruleOff(opts);
	EXPECT_TRUE(SemanticMap(opts).reported(o)) << "rule off";
}
}  // namespace

TEST(SemanticMap, DoubtfulStairsNarrowerThanAFlightAreNotReported)
{
	// indoor_59: a low box and a wastebasket, 0.54 m wide together, detected as
	// stairs in 4 of 4 views with shape score 0.64. A flight's detections are
	// 0.74 m wide and more.
	const auto box = doubtful(Label::Stairs, 2, 0, 0.6, {0.54, 0.54, 0.68});
	const auto flight = doubtful(Label::Stairs, 2, 0, 0.6, {0.96, 0.98});
	EXPECT_TRUE(SemanticMap().reported(flight));
	expectHeldBackOnlyWhileDoubtful(
	    box, 0.99, [](auto& o) { o.unsureStairsMinWidth = 0; });
	auto loaded = box;  // a loaded map has no sighting sizes
	loaded.sightings.clear();
	loaded.sightingSizes.clear();
	EXPECT_TRUE(SemanticMap().reported(loaded));
}

TEST(SemanticMap, DoubtfulWastebasketsNeverSeenNarrowAreNotReported)
{
	// indoor_41: a plant pot (foliage 0.63 m across), 0.40 and 0.38 m wide
	// (shape score 0.66); indoor_148's real wastebasket was seen 0.51 m
	// wide once (its box took in a neighbour) and 0.23 m the other time.
	const auto stool = doubtful(Label::Wastebasket, 2, 0, 0.46, {0.40, 0.38});
	const auto bin = doubtful(Label::Wastebasket, 2, 0, 0.46, {0.51, 0.23});
	EXPECT_TRUE(SemanticMap().reported(bin));
	expectHeldBackOnlyWhileDoubtful(
	    stool, 0.95, [](auto& o) { o.unsureWastebasketMaxWidth = 0; });
}

TEST(SemanticMap, AWellScoredWastebasketSeenOnlyWideIsReported)
{
	// indoor_14 / indoor_138: real bins seen once, from a corner, 0.36 and
	// 0.44 m wide (shape scores 0.93 and 0.90); the false wastebaskets the
	// doubtful rules hold back on tuning buildings 0-159 scored at most 0.77.
	auto bin = doubtful(Label::Wastebasket, 2, 0, 0.44, {0.36}, 0.93);
	EXPECT_TRUE(SemanticMap().reported(bin));
	SemanticMap::TOptions noException;
	noException.unsureWastebasketWideMinShapeScore = 0;
	EXPECT_FALSE(SemanticMap(noException).reported(bin));
	bin.bestShapeScore = 0.77;
	EXPECT_FALSE(SemanticMap().reported(bin)) << "scored as a plant pot";
}

TEST(SemanticMap, ADoubtfulObjectOnASureOneOfAnotherLabelIsNotReported)
{
	// indoor_77: a wastebasket (sure, 5 detections), also detected as a
	// washbasin (shape score 0.66) 0.15 m from it.
	for (const double distance : {0.3, 0.0})
	{
		SemanticMap::TOptions o;
		o.washbasinMaxWallDistance = 0;  // no wall in this map
		o.unsureOtherLabelDistance = distance;
		SemanticMap m(o);
		m.addInstance(Label::Wastebasket, {1.9, -0.1, 0}, {2.1, 0.1, 0.36}, 5);
		ASSERT_EQ(m.instances(Label::Wastebasket).size(), 1u);
		const auto basin = doubtful(Label::Washbasin, 2, 0.15, 0.8, {0.5, 0.5});
		EXPECT_EQ(m.reported(basin), distance == 0) << distance;
		auto sure = basin;
		sure.bestShapeScore = 1;
		EXPECT_TRUE(m.reported(sure)) << "two sure objects both stay";
		const auto beside =
		    doubtful(Label::Washbasin, 2, 0.45, 0.8, {0.5, 0.5});
		EXPECT_TRUE(m.reported(beside)) << "0.45 m away";
	}
}

TEST(SemanticMap, ADoubtfulObjectScoringWellNeedsOneDetection)
{
	// indoor_6, 34, 36: wastebaskets seen in one sweep, detected there with
	// shape scores 0.90-0.94; the false objects detected once scored
	// 0.40-0.75.
	const auto good = doubtful(Label::Wastebasket, 2, 0, 0.4, {0.25}, 0.9);
	const auto poor = doubtful(Label::Wastebasket, 2, 0, 0.4, {0.25}, 0.7);
	SemanticMap::TOptions o, off;
	o.unsureOnceMinShapeScore = 0.8;
	off.unsureOnceMinShapeScore = 0;
	EXPECT_TRUE(SemanticMap(o).reported(good));
	EXPECT_FALSE(SemanticMap(o).reported(poor));
	EXPECT_FALSE(SemanticMap(off).reported(good)) << "rule off";
	// Detected once in two views: the ratio still holds it back.
	auto twice = good;
	twice.views = 2;
	EXPECT_FALSE(SemanticMap(o).reported(twice));
}

TEST(SemanticMap, NamesTheRuleThatHoldsACandidateBack)
{
	// semnav-map --json lists the candidates not reported with these keys.
	const SemanticMap m;
	EXPECT_EQ(
	    m.unreportedReason(doubtful(Label::Stairs, 2, 0, 0.6, {0.96, 0.98})),
	    "");
	EXPECT_EQ(
	    m.unreportedReason(doubtful(Label::Stairs, 2, 0, 0.6, {0.54, 0.54})),
	    "unsure_stairs_min_width_m");
	EXPECT_EQ(
	    m.unreportedReason(
	        doubtful(Label::Wastebasket, 2, 0, 0.46, {0.40, 0.38})),
	    "unsure_wastebasket_max_width_m");
	EXPECT_EQ(
	    m.unreportedReason(doubtful(Label::Wastebasket, 2, 0, 0.4, {0.25})),
	    "unsure_min_observations");
	auto seldom = doubtful(Label::Wastebasket, 2, 0, 0.4, {0.25, 0.25}, 1);
	seldom.views = 5;
	EXPECT_EQ(m.unreportedReason(seldom), "sure_min_detection_ratio");
	auto door = doubtful(Label::Door, 2, 0, 2.05, {0.9}, 0.6);
	door.views = 4;  // detected in one of the four sweeps it was in view
	EXPECT_EQ(m.unreportedReason(door), "door_min_detection_ratio");
	door.views = 6;  // sure (seen whole, square on) but in six views
	door.bestShapeScore = 1;
	EXPECT_EQ(m.unreportedReason(door), "door_sure_min_detection_ratio");
	door.views = 1;
	EXPECT_EQ(m.unreportedReason(door), "");
	door.sightingSizes[0].x = 0.2;
	EXPECT_EQ(m.unreportedReason(door), "door_min_width_m");
}
