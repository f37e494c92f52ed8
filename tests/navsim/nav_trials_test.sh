#!/usr/bin/env bash
# scripts/nav-trials end to end on two starts of one scene (outcomes are the
# localizer's; only their bookkeeping is checked), and its bad input.
# Usage: nav_trials_test.sh SOURCE_DIR APPS_DIR
set -uo pipefail
SRC=$1 BIN=$2
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

"$SRC/scripts/nav-trials" --bin "$BIN" --scene /nonexistent.yaml >"$OUT/o" 2>"$OUT/e"
[ $? -eq 2 ] || fail "a missing scene must exit 2"
[ "$(wc -l <"$OUT/e")" -eq 1 ] && grep -q nonexistent "$OUT/e" || fail "one line naming the scene: $(cat "$OUT/e")"
"$SRC/scripts/nav-trials" --bin "$BIN" --loc-config "$SRC/config/localization.ini" \
  --nav-config "$SRC/config/navigation.ini" --nav-config "$SRC/config/navigation.ini" 2>"$OUT/e" >/dev/null
[ $? -eq 2 ] && grep -q -- --nav-config "$OUT/e" || fail "two --nav-config for one column must exit 2"

"$SRC/scripts/nav-trials" --bin "$BIN" --scene "$SRC/datasets/nav-trials/u_room.yaml" \
  --max-starts 2 --loc-config "walls=$SRC/config/localization.ini" --out "$OUT/t" >"$OUT/table" 2>"$OUT/e" \
  || fail "nav-trials failed: $(tail -3 "$OUT/e")"
python3 - "$OUT/t/runs.json" "$OUT/table" <<'PY' || exit 1
import json, sys
j = json.load(open(sys.argv[1]))
table = open(sys.argv[2]).read()
runs = j["runs"]
assert len(runs) == 2, len(runs)
assert list(j["configs"]) == ["walls"], j["configs"]
for r in runs:
    assert r["outcome"] in ("arrival", "false arrival", "refusal", "other"), r
    assert r["scene"] == "u_room" and r["goal"] == "wastebasket", r
    # an outcome from semnav-nav's JSON agrees with it
    if r["summary"] is not None:
        s = r["summary"]
        assert (r["outcome"] == "arrival") == s["success"], r
        assert (r["outcome"] == "false arrival") == s["false_arrival"], r
counts = {o: sum(1 for r in runs if r["outcome"] == o)
          for o in ("arrival", "false arrival", "refusal", "other")}
for label, o in (("arrivals (true)", "arrival"), ("false arrivals", "false arrival"),
                 ("refusals", "refusal"), ("other failures", "other")):
    assert "| %s | %d / 2" % (label, counts[o]) in table, (label, table)
assert j["maps"]["u_room"]["rmse_xy_m"] is not None
PY
echo "nav-trials: ok"
