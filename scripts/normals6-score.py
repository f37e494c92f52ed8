#!/usr/bin/env python3
"""Compare out/n6/{base,8,16}/results: per-class pixel F1 mean / p5 (scripts/eval-generated's
summarize), per-scene door moves, detection counts. Only scenes present in every variant."""
import importlib.machinery, importlib.util, json, os, sys
ldr = importlib.machinery.SourceFileLoader("eg", "scripts/eval-generated")
spec = importlib.util.spec_from_loader("eg", ldr); eg = importlib.util.module_from_spec(spec); ldr.exec_module(eg)
V = ["base", "8", "16"]
names = set.intersection(*[set(f[:-5] for f in os.listdir("out/n6/%s/results" % v)) for v in V])
res = {v: {n: json.load(open("out/n6/%s/results/%s.json" % (v, n))) for n in names} for v in V}
summ = {v: eg.summarize(list(res[v].values()), 200) for v in V}
for kind in ("indoor", "outdoor"):
    if kind not in summ["base"]: continue
    print("## %s (%d scenes: %s)" % (kind, summ["base"][kind]["scenes"], eg.compact(sorted(summ["base"][kind]["seeds"]))))
    print("| class | off mean / p5 | 8 mean / p5 | 16 mean / p5 |\n|---|---|---|---|")
    for c in sorted(summ["base"][kind]["pixel_f1"]):
        row = ["%.4f / %.4f" % (summ[v][kind]["pixel_f1"][c]["mean"], summ[v][kind]["pixel_f1"][c]["p5"]) for v in V]
        print("| %s (%d) | %s |" % (c, summ["base"][kind]["pixel_f1"][c]["scenes"], " | ".join(row)))
    print("objects tp/fp/fn:", {v: {c: "%d/%d/%d" % (o["tp"], o["fp"], o["fn"]) for c, o in summ[v][kind]["objects"].items()} for v in V})
    same = {v: all(res[v][n]["objects"] == res["base"][n]["objects"] for n in names if n.startswith(kind)) for v in ("8", "16")}
    print("detections per scene identical to off:", same)
    for c in ("door", "obstacle", "wall") if kind == "indoor" else ("door", "wall", "obstacle", "sidewalk", "grass"):
        mv = []
        for n in sorted(names, key=lambda s: (s.split("_")[0], int(s.split("_")[1]))):
            if not n.startswith(kind): continue
            p = [res[v][n]["pixels"].get(c, {}) for v in V]
            if p[0].get("pixels", 0) < 200: continue
            d8, d16 = p[1]["f1"] - p[0]["f1"], p[2]["f1"] - p[0]["f1"]
            if abs(d8) >= 0.02 or abs(d16) >= 0.02: mv.append("%s %.3f %+.3f/%+.3f" % (n.split("_")[1], p[0]["f1"], d8, d16))
        print("%s moves >= 0.02 (scene off 8/16): %s" % (c, "; ".join(mv)))
print("object count differences per scene (scene class: off -> 8 / 16, tp/fp/fn):")
for n in sorted(names):
    for c in ("washbasin", "wastebasket", "stairs"):
        o = [res[v][n]["objects"].get(c, {}) for v in V]
        t = ["%d/%d/%d" % (x.get("tp", 0), x.get("fp", 0), x.get("fn", 0)) for x in o]
        if len(set(t)) > 1: print("  %s %s: %s -> %s / %s" % (n, c, *t))
