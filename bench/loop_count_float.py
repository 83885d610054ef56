#!/usr/bin/python3
"""An independent float count of the bounded loops of the curve A ∩ B (two quadrics as 4x4
matrices), for checking proven_loops by hand: not a proof, a dense-sampling witness.

The curve is sampled on the planes x_k = c, k = 0, 1, 2, c on a grid of spacing h over
[-R, R]: in each plane both quadrics are conics; their common points come from the quartic
resultant in one coordinate (numpy roots, polished by Newton in the plane). Sampled along all
three axes, consecutive samples on one component are at most ~sqrt(3) h apart (the tangent has
a component >= 1/sqrt(3) along some axis); the samples are clustered by single linkage at
distance 3 h (grid hashing). A cluster whose samples all stay within 0.8 R of the origin is a
loop; one reaching the border of [-R, R]^3 is a piece of an unbounded branch. Run at two
resolutions: the counts must agree (components closer than 3 h would merge).

Usage: loop_count_float.py 'A as JSON 4x4' 'B as JSON 4x4' [--R 20] [--n 3000]
Prints {"loops": n, "unbounded_pieces": m, "loop_boxes": [[min], [max]] ...} (the boxes in the
rotated frame: the counts are what is compared).
"""
import argparse
import json
from fractions import Fraction as F

import numpy as np


def plane_points(a, b, k, cs):
    """Common points of A and B on the planes x_k = c, c in cs: an (n, 3) array."""
    i, j = (k + 1) % 3, (k + 2) % 3
    order = [k, i, j, 3]
    pa = a[np.ix_(order, order)]
    pb = b[np.ix_(order, order)]
    if pa[2, 2] == 0 and pb[2, 2] == 0:
        order = [k, j, i, 3]
        i, j = j, i
        pa = a[np.ix_(order, order)]
        pb = b[np.ix_(order, order)]
    out = []
    for c in cs:
        # f = q22 z^2 + bz(y) z + c(y), coordinates (x=c, y, z, 1) in the permuted order.
        def parts(m):
            a2 = m[2, 2]
            b1 = np.array([2 * m[1, 2], 2 * (m[0, 2] * c + m[2, 3])])  # in y: b1[0] y + b1[1]
            c2 = np.array([m[1, 1], 2 * (m[0, 1] * c + m[1, 3]),
                           m[0, 0] * c * c + 2 * m[0, 3] * c + m[3, 3]])
            return a2, b1, c2
        a1, b1, c1 = parts(pa)
        a2, b2, c2 = parts(pb)
        p = np.polysub(a1 * c2, a2 * c1)      # a1 c2 - a2 c1 (deg 2)
        q = np.polysub(a1 * b2, a2 * b1)      # a1 b2 - a2 b1 (deg 1)
        r = np.polysub(np.polymul(b1, c2), np.polymul(b2, c1))  # b1 c2 - b2 c1 (deg 3)
        res = np.polysub(np.polymul(p, p), np.polymul(q, r))
        res = np.trim_zeros(res, "f")
        if len(res) < 2:
            continue
        for y in np.roots(res):
            if abs(y.imag) > 1e-6 * (1 + abs(y.real)):
                continue
            y = y.real
            qv = np.polyval(q, y)
            if abs(qv) < 1e-12:
                continue
            z = -np.polyval(p, y) / qv
            pt = np.zeros(4)
            pt[0], pt[1], pt[2], pt[3] = c, y, z, 1.0
            # Newton on (y, z) in the plane.
            for _ in range(3):
                fa, fb = pt @ pa @ pt, pt @ pb @ pt
                ga, gb = 2 * (pa @ pt), 2 * (pb @ pt)
                jac = np.array([[ga[1], ga[2]], [gb[1], gb[2]]])
                try:
                    d = np.linalg.solve(jac, [-fa, -fb])
                except np.linalg.LinAlgError:
                    break
                pt[1] += d[0]
                pt[2] += d[1]
            fa, fb = pt @ pa @ pt, pt @ pb @ pt
            scale = 1 + np.dot(pt, pt)
            if abs(fa) > 1e-8 * scale or abs(fb) > 1e-8 * scale:
                continue
            x = np.zeros(3)
            x[k], x[i], x[j] = pt[0], pt[1], pt[2]
            out.append(x)
    return out


def count(a, b, R, n):
    # A fixed generic rotation first (the count does not move): axis-aligned pairs (a cylinder
    # along z) make the subresultant in a slice vanish identically.
    rot, _ = np.linalg.qr(np.random.default_rng(7).normal(size=(3, 3)))
    t = np.eye(4)
    t[:3, :3] = rot
    a, b = t.T @ a @ t, t.T @ b @ t
    cs = np.linspace(-R, R, n)
    h = cs[1] - cs[0]
    pts = []
    for k in range(3):
        pts += plane_points(a, b, k, cs)
    pts = np.array(pts)
    if len(pts) == 0:
        return {"loops": 0, "unbounded_pieces": 0, "loop_boxes": []}
    pts = pts[np.all(np.abs(pts) <= R, axis=1)]
    tau = 3 * h
    cell = {}
    keys = np.floor(pts / tau).astype(np.int64)
    for idx, key in enumerate(map(tuple, keys)):
        cell.setdefault(key, []).append(idx)
    parent = list(range(len(pts)))

    def find(x):
        while parent[x] != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x
    for key, members in cell.items():
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for dz in (-1, 0, 1):
                    other = cell.get((key[0] + dx, key[1] + dy, key[2] + dz))
                    if not other:
                        continue
                    for p in members:
                        for q in other:
                            if q > p and np.linalg.norm(pts[p] - pts[q]) <= tau:
                                rp, rq = find(p), find(q)
                                if rp != rq:
                                    parent[rp] = rq
    comps = {}
    for p in range(len(pts)):
        comps.setdefault(find(p), []).append(p)
    loops, unbounded, boxes = 0, 0, []
    for members in comps.values():
        c = pts[members]
        if len(members) < 8:
            continue  # a few samples of a tiny piece: reported below as not counted
        if np.max(np.abs(c)) < 0.8 * R:
            loops += 1
            boxes.append([c.min(axis=0).round(4).tolist(), c.max(axis=0).round(4).tolist()])
        else:
            unbounded += 1
    return {"loops": loops, "unbounded_pieces": unbounded, "loop_boxes": boxes,
            "samples": len(pts), "h": h}


def matrix(text):
    return np.array([[float(F(str(x))) for x in row] for row in json.loads(text)])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("a")
    ap.add_argument("b")
    ap.add_argument("--R", type=float, default=20)
    ap.add_argument("--n", type=int, default=3000)
    args = ap.parse_args()
    a, b = matrix(args.a), matrix(args.b)
    fine = count(a, b, args.R, args.n)
    coarse = count(a, b, args.R, args.n // 2)
    fine["agrees_at_half_resolution"] = coarse["loops"] == fine["loops"]
    print(json.dumps(fine))


if __name__ == "__main__":
    main()
