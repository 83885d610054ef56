#!/usr/bin/python3
"""Random natural-quadric pairs through `surfcert batch` (op intersect): how many answers are
certified / undecided, and whether a certified answer's crossings with its box are wrong.

Natural quadrics: planes, spheres, circular cylinders and circular cones, posed by small integer
quaternions (exact rational rotations) at half-integer centres, so that parallel axes, shared
apices and tangencies occur now and then. Each pair is written as two exact 4x4 matrices.

The independent check of a certified box answer: on each face of the reported box, both
quadrics are restricted to the face (a conic each) and sampled on a 600 x 600 grid; cells where
both conics change sign are clustered (8-connectivity); the number of clusters is a dense,
independent count of the crossings, compared with result.box.exits.count (a cluster within
three cells of the face's border is 'unclear'). When the grid disagrees or is unclear, sympy
decides: the two face conics solved exactly (sympy.solve, radicals), the solutions evaluated
to 40 digits, the real ones inside the face counted; a pair counts as wrong only when sympy
disagrees too.

Usage: natural_box_pairs.py SURFCERT [--count 300] [--seed 1] [--dump pairs.jsonl]
Prints one summary line (JSON) and writes the disagreements to stderr.
"""
import argparse
import json
import random
import subprocess
import sys
from fractions import Fraction as F

import numpy as np


def rotation(rng):
    while True:
        q = [rng.randint(-2, 2) for _ in range(4)]
        if rng.random() < 0.4:
            q = [1, 0, 0, 0]
        n = sum(c * c for c in q)
        if n:
            break
    w, x, y, z = q
    r = [[w*w + x*x - y*y - z*z, 2*(x*y - w*z), 2*(x*z + w*y)],
         [2*(x*y + w*z), w*w - x*x + y*y - z*z, 2*(y*z - w*x)],
         [2*(x*z - w*y), 2*(y*z + w*x), w*w - x*x - y*y + z*z]]
    return [[F(r[i][j], n) for j in range(3)] for i in range(3)]


def natural(rng):
    kind = rng.choice(["plane", "sphere", "cylinder", "cone"])
    r = rotation(rng)
    c = [F(rng.randint(-4, 4), 2) for _ in range(3)]
    rad = F(rng.randint(1, 6), 2)
    # unit shape S (local coords), 4x4 diag
    if kind == "plane":
        s = None
    elif kind == "sphere":
        s = [1, 1, 1, -rad * rad]
    elif kind == "cylinder":
        s = [1, 1, 0, -rad * rad]
    else:
        s = [1, 1, -rad * rad, 0]
    # world -> local: l = R^T (x - c); matrix P with l_hom = P x_hom
    p = [[r[j][i] for j in range(3)] + [-sum(r[j][i] * c[j] for j in range(3))] for i in range(3)]
    p.append([F(0), F(0), F(0), F(1)])
    if kind == "plane":  # local z = 0: linear form, as a symmetric matrix
        m = [[F(0)] * 4 for _ in range(4)]
        for i in range(4):
            m[i][3] += p[2][i] / 2
            m[3][i] += p[2][i] / 2
        return kind, m
    m = [[sum(p[k][i] * F(s[k]) * p[k][j] for k in range(4)) for j in range(4)] for i in range(4)]
    return kind, m


def face_count(ma, mb, box, axis, value, n=600):
    lo, hi = box["min"], box["max"]
    i, j = (axis + 1) % 3, (axis + 2) % 3
    u = np.linspace(lo[i], hi[i], n)
    v = np.linspace(lo[j], hi[j], n)
    uu, vv = np.meshgrid(u, v, indexing="ij")
    pts = np.zeros((4,) + uu.shape)
    pts[i], pts[j], pts[axis], pts[3] = uu, vv, value, 1.0

    def sgn(m):
        a = np.array([[float(x) for x in row] for row in m])
        f = np.einsum("i...,ij,j...->...", pts, a, pts)
        return np.sign(f)

    def changes(s):
        c = np.minimum.reduce([s[:-1, :-1], s[1:, :-1], s[:-1, 1:], s[1:, 1:]])
        d = np.maximum.reduce([s[:-1, :-1], s[1:, :-1], s[:-1, 1:], s[1:, 1:]])
        return (c <= 0) & (d >= 0)

    both = changes(sgn(ma)) & changes(sgn(mb))
    seen = np.zeros_like(both)
    clusters, unclear = 0, 0
    for a0, b0 in zip(*np.nonzero(both)):
        if seen[a0, b0]:
            continue
        stack, border = [(a0, b0)], False
        seen[a0, b0] = True
        while stack:
            a1, b1 = stack.pop()
            border = border or min(a1, b1) < 3 or max(a1, b1) > n - 5
            for da in (-1, 0, 1):
                for db in (-1, 0, 1):
                    a2, b2 = a1 + da, b1 + db
                    if 0 <= a2 < n - 1 and 0 <= b2 < n - 1 and both[a2, b2] and not seen[a2, b2]:
                        seen[a2, b2] = True
                        stack.append((a2, b2))
        if border:
            unclear += 1
        else:
            clusters += 1
    return clusters, unclear


def sympy_count(ma, mb, box):
    import sympy as sp
    u, v = sp.symbols("u v")
    total = 0
    for axis in range(3):
        for val in (box["min"][axis], box["max"][axis]):
            i, j = (axis + 1) % 3, (axis + 2) % 3
            x = [0] * 4
            x[i], x[j], x[axis], x[3] = u, v, sp.Rational(F(val)), 1
            form = lambda m: sp.expand(sum(x[p] * sp.Rational(m[p][q]) * x[q]
                                           for p in range(4) for q in range(4)))
            fa, fb = form(ma), form(mb)
            for sol in sp.solve([fa, fb], [u, v], dict=True):
                if u not in sol or v not in sol:
                    return None  # a common component on the face
                r, w = sp.N(sol[u], 40), sp.N(sol[v], 40)
                if abs(sp.im(r)) > 1e-25 or abs(sp.im(w)) > 1e-25:
                    continue
                r, w = sp.re(r), sp.re(w)
                if (box["min"][i] < r < box["max"][i]) and (box["min"][j] < w < box["max"][j]):
                    total += 1
    return total


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("surfcert")
    ap.add_argument("--count", type=int, default=300)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--dump", help="write the batch input lines here")
    args = ap.parse_args()
    rng = random.Random(args.seed)
    pairs, lines = [], []
    for k in range(args.count):
        ka, ma = natural(rng)
        kb, mb = natural(rng)
        pairs.append((ka, kb, ma, mb))
        enc = lambda m: {"matrix": [[str(x) for x in row] for row in m]}
        lines.append(json.dumps({"id": k, "op": "intersect", "a": enc(ma), "b": enc(mb),
                                 "detail": "topology"}))
    if args.dump:
        with open(args.dump, "w") as f:
            f.write("\n".join(lines) + "\n")
    res = subprocess.run([args.surfcert, "batch", "--threads", "1"], input="\n".join(lines) + "\n",
                         capture_output=True, text=True)
    out = {"certified": 0, "undecided": 0, "other": 0, "box_checked": 0, "wrong": 0,
           "grid_disagrees": 0, "exits_certified": 0, "exits_undecided": 0, "reasons": {}}
    for line in res.stdout.splitlines():
        d = json.loads(line)
        k = d["id"]
        st = d.get("status")
        out[st if st in ("certified", "undecided") else "other"] += 1
        r = d.get("result", {})
        if st != "certified":
            why = d.get("note", "") or r.get("note", "")
            key = why.split(":")[0][:60]
            out["reasons"][key] = out["reasons"].get(key, 0) + 1
        box = r.get("box")
        if not box:
            continue
        ex = box.get("exits")
        if ex is not None:
            out["exits_certified" if ex["status"] == "certified" else "exits_undecided"] += 1
        if st != "certified":
            continue
        ka, kb, ma, mb = pairs[k]
        total, unclear = 0, 0
        for axis in range(3):
            for value in (box["min"][axis], box["max"][axis]):
                c, u = face_count(ma, mb, box, axis, value)
                total += c
                unclear += u
        out["box_checked"] += 1
        # The certified count: the exact crossings (new) or, before, twice the open pieces.
        claimed = ex["count"] if ex is not None else 2 * sum(
            1 for b in r.get("branches", []) if not b["closed"])
        if unclear or total != claimed:
            out["grid_disagrees"] += 1
            total = sympy_count(ma, mb, box)
        if total != claimed:
            out["wrong"] += 1
            print(f"pair {k} ({ka} x {kb}): certified {claimed} crossings, independent count {total}",
                  file=sys.stderr)
    print(json.dumps(out))


if __name__ == "__main__":
    main()
