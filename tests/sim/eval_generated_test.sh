#!/usr/bin/env bash
# scripts/eval-generated's bad input (one line each, nothing run): a bad seed
# list, a mix of tuning and test seeds, --remap without --map, no --jobs or
# a missing --map-config exits 2, a missing build exits 1.
# Usage: eval_generated_test.sh SOURCE_DIR APPS_DIR
set -uo pipefail
SRC=$1 BIN=$2
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

expect() {  # CODE ARGS...
	local code=$1
	shift
	"$SRC/scripts/eval-generated" --out "$OUT/run" "$@" >"$OUT/o" 2>"$OUT/e"
	local got=$?
	[ "$got" -eq "$code" ] || fail "$* exited $got, not $code: $(cat "$OUT/e")"
	[ "$(wc -l <"$OUT/e")" -eq 1 ] || fail "$*: not one line: $(cat "$OUT/e")"
	grep -q '^eval-generated: ' "$OUT/e" || fail "$*: unnamed: $(cat "$OUT/e")"
}
expect 2 --bin "$BIN" --indoor 5-x
expect 2 --bin "$BIN" --indoor 9-3
expect 2 --bin "$BIN" --indoor 1,1
expect 2 --bin "$BIN" --indoor 999-1000
expect 2 --bin "$BIN"
expect 2 --bin "$BIN" --indoor 1 --remap
expect 2 --bin "$BIN" --indoor 1 --jobs 0
expect 2 --bin "$BIN" --indoor 1 --map --map-config "$OUT/none.ini"
expect 1 --bin "$OUT/no-build" --outdoor 1000
[ ! -e "$OUT/run" ] || fail "a refused run must not create its output"
echo "eval-generated: ok"
