#!/usr/bin/env python3
"""scripts/eval-generated --map: how the map's objects are scored against a
scene's objects (found once, duplicated, far, missed, spurious; an object
the trajectory did not see does not count). Usage: eval_generated_map_test.py
SOURCE_DIR"""
import importlib.machinery
import importlib.util
import sys

src = sys.argv[1]
loader = importlib.machinery.SourceFileLoader(
    "eval_generated", src + "/scripts/eval-generated")
spec = importlib.util.spec_from_loader("eval_generated", loader)
ev = importlib.util.module_from_spec(spec)
loader.exec_module(ev)

INI = ev.DEFAULT_MAP_CONFIG
need = max(ev.map_ini_value(INI, "min_observations"),
           ev.map_ini_value(INI, "door_min_observations"))
SEEN = [ev.SEEN_PIXELS] * need       # seen by `need` sweeps
UNSEEN = [ev.SEEN_PIXELS - 1] * 5    # never enough pixels


def obj(i, label, x, y, pixels=SEEN):
    return {"id": i, "label": label, "x": x, "y": y, "sweep_pixels": pixels}


def rep(i, label, x, y):
    return {"id": i, "label": label, "x": x, "y": y, "observations": 3}


truth = [
    obj(1, "door", 0, 0),                 # found once
    obj(2, "door", 5, 0),                 # two reported: duplicated
    obj(3, "door", 10, 0),                # reported 0.6 m away: far
    obj(4, "door", 15, 0),                # nothing near: missed
    obj(5, "door", 20, 0, UNSEEN),        # not seen: does not count
    obj(6, "wastebasket", 0, 5),          # seen (recognisable views)
    obj(7, "wastebasket", 3, 5),          # pixels, no recognisable view
    obj(8, "obstacle", 6, 5),
    obj(9, "door", 25, 0),                # pixels, beside the robot only
    obj(10, "door", 35, 0, UNSEEN),       # not seen, reported 0.6 m off
]
reported = [
    rep(1, "door", 0.1, 0.1), rep(2, "door", 5.1, 0), rep(3, "door", 4.9, 0),
    rep(4, "door", 10.6, 0), rep(5, "door", 20.2, 0),   # near the unseen one
    dict(rep(6, "door", 30, 0), observations=1),         # spurious, once
    rep(7, "wastebasket", 0.05, 5), rep(8, "wastebasket", 6, 5),  # spurious
    rep(9, "door", 35.6, 0),             # misplaced, not spurious
]
views = {"1": need, "2": need, "3": need, "4": need, "6": need, "7": 0,
         "9": 0}
s = ev.score_map(truth, reported, views, INI)
by_pixels = ev.score_map(truth, reported, views, INI, doors_by_pixels=True)

failed = []


def check(cls, scores=None, **want):
    scores = scores or s
    for k, v in want.items():
        if scores[cls][k] != v:
            failed.append("%s %s: %s, want %s" % (cls, k, scores[cls][k], v))


check("door", seen=4, found=1, duplicated=1, far=1, missed=1, spurious=1,
      far_unseen=1, reported=7, reported_once=1)
check("door", by_pixels, seen=5, found=1, missed=2, spurious=1)
check("wastebasket", seen=1, found=1, missed=0, spurious=1, reported=2)
check("stairs", seen=0, reported=0, spurious=0)
whats = sorted(f["what"] for f in s["door"]["failures"])
if whats != ["duplicated", "far", "missed", "spurious"]:
    failed.append("door failures: %s" % whats)

summary = ev.summarize_maps([
    {"map": s, "map_pixel_rule": by_pixels},
    {"map": ev.score_map(truth[:1], reported[:1], {}, INI),
     "map_pixel_rule": ev.score_map(truth[:1], reported[:1], {}, INI, True)}])
if summary["buildings"] != 2 or summary["no_spurious_share"] != 0.5 or \
        summary["all_seen_found_once_share"] != 0.5 or \
        summary["classes"]["door"]["reported_once"] != 1 or \
        summary["classes"]["door"]["seen"] != 4 or \
        summary["pixel_rule"]["classes"]["door"]["seen"] != 6:
    failed.append("summary: %s" % summary)

for f in failed:
    print("FAIL: " + f)
print("eval-generated --map scoring: %s" % ("FAILED" if failed else "ok"))
sys.exit(1 if failed else 0)
