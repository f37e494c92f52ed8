#!/usr/bin/env python3
"""Perceive + detect the scenes of out/n6/base/sim with out/n6/bin-V (V = 0 via bin-a, 8, 16);
results in the format of scripts/eval-generated's results/KIND_N.json.
usage: run.py VARIANT [perceive-only] NAMES..."""
import json, os, subprocess, sys
v = sys.argv[1]; args = sys.argv[2:]
ponly = args and args[0] == "perceive-only"
if ponly: args = args[1:]
B = "out/n6/base"; BIN = "out/n6/bin-" + v; O = "out/n6/" + v
os.makedirs(O + "/results", exist_ok=True)
def last_json(t):
    return json.loads([l for l in t.splitlines() if l.startswith("{")][-1])
for name in args:
    res = O + "/results/" + name + ".json"
    if os.path.exists(res): continue
    sim = B + "/sim/" + name
    base = json.load(open(B + "/results/" + name + ".json"))
    p = last_json(subprocess.run(["nice", "-n", "10", BIN + "/semnav-perceive", "--rawlog", sim + "/" + name + ".rawlog",
        "--gt-dir", sim, "--out", O + "/perceive/" + name, "--json"], capture_output=True, text=True, check=True).stdout)
    r = dict(base); r["pixels"] = p.get("classes", {}); r["sweeps"] = p.get("sweeps")
    if not ponly:
        d = last_json(subprocess.run(["nice", "-n", "10", BIN + "/semnav-detect", "--config", "config/cascade.ini", "--json",
            "--datasets", sim], capture_output=True, text=True, check=True).stdout)
        r["objects"] = {c: d.get("objects_recognisable", {}).get(c, {}) for c in ("washbasin", "wastebasket", "stairs")}
    else:
        r.pop("objects", None)
    json.dump(r, open(res, "w"))
    print(name, flush=True)
