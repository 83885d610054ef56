#!/usr/bin/env python3
"""Compare two SURFCERT_DUMP files of intersect_peers_bench: every field identical except the
traced polylines (branches[*].points: compared as counts and max coordinate deviation) and
max_residual (a measure of those points). Exit status 1 when any other field differs.

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
        if a != b or type(a) != type(b):
            diffs.append(f"{path}: {a!r} vs {b!r}")

A = [json.loads(l) for l in open(sys.argv[1])]
B = [json.loads(l) for l in open(sys.argv[2])]
assert len(A) == len(B), (len(A), len(B))
soft = dict(points_a=0, points_b=0, maxdev=0.0, npts_differ=0, residual=0.0)
bad = 0
for x, y in zip(A, B):
    diffs = []
    walk(x, y, "", diffs, soft)
    if diffs:
        bad += 1
        if bad <= 10:
            print(f"pair {x['index']} ({x['case']}):", *diffs[:8], sep="\n  ")
print(f"{len(A)} pairs, {bad} with differences in exact/certified fields; points {soft['points_a']} vs "
      f"{soft['points_b']}, {soft['npts_differ']} branches with other point counts, max point "
      f"deviation (same counts) {soft['maxdev']:.3g}, max residual {soft['residual']:.3g}")
sys.exit(1 if bad else 0)
