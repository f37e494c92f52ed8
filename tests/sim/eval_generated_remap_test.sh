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
echo "eval-generated --remap: ok ($first doors seen, then 0)"
