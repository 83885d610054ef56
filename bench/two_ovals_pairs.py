#!/usr/bin/python3
"""Random general quadric pairs (symmetric 4x4 integer matrices, entries in [-5, 5], both
surfaces with real points) through `surfcert batch` (op intersect): how the two_ovals pairs with
four real points at infinity are answered, and which of them have det(lA - B) irreducible over
Q (no member of the pencil is a cone or cylinder with a rational apex, so
certify/cone_ovals.hpp cannot split the points at infinity among the ovals).

The loop counts certified there can be checked independently, pair by pair, with
bench/loop_count_float.py (dense plane sampling).

Usage: two_ovals_pairs.py SURFCERT [--count 2000] [--seed 1] [--dump pairs.jsonl]
Prints one JSON line per two_ovals pair with 4 points at infinity (its matrices, status, affine
route and counts, irreducibility), then a summary line.
"""
import argparse
import json
import random
import subprocess
import sys

import sympy as sp


def real_points(m, rng):
    # A nonsingular quadric has real points iff its form takes both signs on R^3: sampled.
    pos = neg = False
    for _ in range(400):
        x = [rng.uniform(-10, 10) for _ in range(3)] + [1.0]
        f = sum(x[i] * m[i][j] * x[j] for i in range(4) for j in range(4))
        pos, neg = pos or f > 0, neg or f < 0
        if pos and neg:
            return True
    return False


def random_quadric(rng):
    while True:
        m = [[0] * 4 for _ in range(4)]
        for i in range(4):
            for j in range(i, 4):
                m[i][j] = m[j][i] = rng.randint(-5, 5)
        if sp.Matrix(m).det() != 0 and sp.Matrix(3, 3, lambda i, j: m[i][j]).det() != 0 \
                and real_points(m, rng):
            return m


def char_poly(a, b):
    lam = sp.Symbol("l")
    return sp.Poly(sp.Matrix(4, 4, lambda i, j: lam * a[i][j] - b[i][j]).det(), lam)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("surfcert")
    ap.add_argument("--count", type=int, default=2000)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--dump", help="write the batch input lines of the two_ovals pairs here")
    args = ap.parse_args()
    rng = random.Random(args.seed)
    pairs, lines = [], []
    for k in range(args.count):
        a, b = random_quadric(rng), random_quadric(rng)
        pairs.append((a, b))
        lines.append(json.dumps({"id": k, "op": "intersect", "a": {"matrix": a},
                                 "b": {"matrix": b}}))
    res = subprocess.run([args.surfcert, "batch", "--threads", "1"], input="\n".join(lines) + "\n",
                         capture_output=True, text=True)
    summary = {"pairs": args.count, "two_ovals_4": 0, "irreducible": 0, "certified": 0,
               "undecided": 0, "irreducible_undecided": 0, "affine_undecided": 0}
    dump = []
    for line in res.stdout.splitlines():
        d = json.loads(line)
        r = d.get("result", {})
        if r.get("morphology") != "two_ovals":
            continue
        af = r.get("affine") or {}
        pts = af.get("points_at_infinity") or []
        if len(pts) != 4:
            continue
        k = d["id"]
        a, b = pairs[k]
        irreducible = char_poly(a, b).is_irreducible
        summary["two_ovals_4"] += 1
        summary["irreducible"] += irreducible
        summary[d["status"] if d["status"] in ("certified", "undecided") else "undecided"] += 1
        if af.get("status") != "certified":
            summary["affine_undecided"] += 1
        if irreducible and d["status"] != "certified":
            summary["irreducible_undecided"] += 1
        print(json.dumps({"id": k, "status": d["status"], "affine": af.get("status"),
                          "route": af.get("route"), "loops": af.get("loops"),
                          "unbounded": af.get("unbounded_branches"),
                          "irreducible": irreducible, "note": r.get("note", "")[:100],
                          "a": a, "b": b}))
        dump.append(lines[k])
    if args.dump:
        with open(args.dump, "w") as f:
            f.write("\n".join(dump) + "\n")
    print(json.dumps(summary))


if __name__ == "__main__":
    main()
