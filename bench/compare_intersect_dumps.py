#!/usr/bin/env python3
"""Compare two SURFCERT_DUMP files of intersect_peers_bench: every field identical except the
traced polylines (branches[*].points: compared as counts and max coordinate deviation) and
max_residual (a measure of those points), and the box crossings' double estimates
(box.exits.points: midpoints of enclosures, which two routes may round differently in the last
bits: compared within 1e-12 relative, their largest deviation reported). Exit status 1 when any
other field differs. --all prints every pair that differs (default: the first 10).

Usage: SURFCERT_DUMP=old.jsonl OLD/intersect_peers_bench 20 500; the same for new.jsonl;
python3 bench/compare_intersect_dumps.py old.jsonl new.jsonl"""
import json, sys, math

def walk(a, b, path, diffs, soft):
    if isinstance(a, dict) and isinstance(b, dict):
        if list(a.keys()) != list(b.keys()):
            diffs.append(f"{path}: keys {list(a.keys())} vs {list(b.keys())}")
            return
        for k in a:
            p = f"{path}.{k}"
            if k == "branches" and isinstance(a[k], list) and isinstance(b[k], list):
                if len(a[k]) != len(b[k]):
                    diffs.append(f"{p}: {len(a[k])} vs {len(b[k])} branches"); continue
                for i, (x, y) in enumerate(zip(a[k], b[k])):
                    xh = {kk: vv for kk, vv in x.items() if kk != "points"}
                    yh = {kk: vv for kk, vv in y.items() if kk != "points"}
                    walk(xh, yh, f"{p}[{i}]", diffs, soft)
                    soft["points_a"] += len(x["points"]); soft["points_b"] += len(y["points"])
                    if len(x["points"]) == len(y["points"]):
                        for u, v in zip(x["points"], y["points"]):
                            soft["maxdev"] = max(soft["maxdev"], max(abs(s - t) for s, t in zip(u, v)))
                    else:
                        soft["npts_differ"] += 1
            elif k == "max_residual":
                soft["residual"] = max(soft["residual"], max(a[k], b[k]))
            else:
                walk(a[k], b[k], p, diffs, soft)
    elif isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            diffs.append(f"{path}: len {len(a)} vs {len(b)}"); return
        for i, (x, y) in enumerate(zip(a, b)):
            walk(x, y, f"{path}[{i}]", diffs, soft)
    else:
        if ".exits.points[" in path and isinstance(a, float) and isinstance(b, float):
            dev = abs(a - b) / (1 + abs(a))
            soft["exitdev"] = max(soft["exitdev"], dev)
            if dev > 1e-12:
                diffs.append(f"{path}: {a!r} vs {b!r}")
        elif a != b or type(a) != type(b):
            diffs.append(f"{path}: {a!r} vs {b!r}")

args = [a for a in sys.argv[1:] if a != "--all"]
show_all = "--all" in sys.argv[1:]
# "ours_us" (the pair's time, dumps since session 28) differs from run to run: not compared.
A = [{k: v for k, v in json.loads(l).items() if k != "ours_us"} for l in open(args[0])]
B = [{k: v for k, v in json.loads(l).items() if k != "ours_us"} for l in open(args[1])]
assert len(A) == len(B), (len(A), len(B))
soft = dict(points_a=0, points_b=0, maxdev=0.0, npts_differ=0, residual=0.0, exitdev=0.0)
bad = 0
for x, y in zip(A, B):
    diffs = []
    walk(x, y, "", diffs, soft)
    if diffs:
        bad += 1
        if bad <= 10 or show_all:
            print(f"pair {x['index']} ({x['case']}):", *diffs[:8], sep="\n  ")
print(f"{len(A)} pairs, {bad} with differences in exact/certified fields; points {soft['points_a']} vs "
      f"{soft['points_b']}, {soft['npts_differ']} branches with other point counts, max point "
      f"deviation (same counts) {soft['maxdev']:.3g}, max residual {soft['residual']:.3g}, max "
      f"relative deviation of box crossings {soft['exitdev']:.3g}")
sys.exit(1 if bad else 0)
