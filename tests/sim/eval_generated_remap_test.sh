#!/usr/bin/env bash
# scripts/eval-generated --map, then --remap with other map settings: the
# second run maps again (a changed door_min_observations changes which doors
# were seen) without simulating, perceiving or detecting again.
# Usage: eval_generated_remap_test.sh SOURCE_DIR APPS_DIR
set -uo pipefail
SRC=$1 BIN=$2
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
EVAL=("$SRC/scripts/eval-generated" --bin "$BIN" --indoor 0 --map --json)

"${EVAL[@]}" --out "$OUT/run" >"$OUT/first.json" 2>"$OUT/e" ||
	fail "first run: $(cat "$OUT/e")"
seen() {  # the doors seen, from a run's result
	python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["map"]["door"]["seen"])' \
		"$OUT/run/results/indoor_0.json"
}
first=$(seen)
[ "$first" -gt 0 ] || fail "no door seen in indoor_0"

sed 's/^door_min_observations = .*/door_min_observations = 50/' \
	"$SRC/config/map.ini" >"$OUT/strict.ini"
"${EVAL[@]}" --out "$OUT/run" --remap --map-config "$OUT/strict.ini" \
	>"$OUT/second.json" 2>"$OUT/e" || fail "--remap: $(cat "$OUT/e")"
[ "$(seen)" -eq 0 ] || fail "--remap kept $(seen) doors seen in 50 sweeps"
grep -q -- "--scene" "$OUT/run/logs/indoor_0.log" &&
	fail "--remap simulated again"
grep -q "semnav-map" "$OUT/run/logs/indoor_0.log" || fail "--remap did not map"

# Doors taller than any: each seen door is missed, and its candidate names
# the rule that held it back (semnav-map --json "not_reported").
sed 's/^door_min_height_m = .*/door_min_height_m = 2.9/' \
	"$SRC/config/map.ini" >"$OUT/tall.ini"
"${EVAL[@]}" --out "$OUT/run" --remap --map-config "$OUT/tall.ini" \
	>"$OUT/third.json" 2>"$OUT/e" || fail "--remap tall: $(cat "$OUT/e")"
python3 - "$OUT/run" "$first" <<'PY' || fail "held-back doors"
import json, sys
run, first = sys.argv[1], int(sys.argv[2])
door = json.load(open(run + "/results/indoor_0.json"))["map"]["door"]
missed = [f for f in door["failures"] if f["what"] == "missed"]
assert door["seen"] == first and door["found"] == 0, door
held = [f["held_back"]["rule"] for f in missed]
assert sum(r.startswith("door_min_height_m") for r in held) >= max(
    1, first // 2), held
summary = json.load(open(run + "/maps/indoor_0.json"))
assert not [o for o in summary["objects"] if o["label"] == "door"]
rules = {o["rule"] for o in summary["not_reported"] if o["label"] == "door"}
assert "door_min_height_m" in rules, rules
PY
echo "eval-generated --remap: ok ($first doors seen, then 0, then held back)"
