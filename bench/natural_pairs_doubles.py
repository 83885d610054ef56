#!/usr/bin/env python3
"""Random natural-quadric intersect pairs posed in doubles, as a `surfcert batch` JSONL file:
the input users send (shapes with double centres, radii and unit quaternions; planes as
equations with double coefficients), for whole-process A/B runs (bench/ab_batch.py).

Kinds: plane, sphere, circular cylinder, circular cone (two planes excluded), each posed by its
own uniformly random rotation (a normalised Gaussian quaternion, rounded to doubles) at a centre
in [-1, 1]^3; radii in [0.3, 1], cone slopes in [0.5, 2]. `--kinds cylinder-plane` keeps only
pairs of those kinds (in either order).

Usage: natural_pairs_doubles.py [--count 300] [--seed 28] [--kinds K1-K2] > pairs.jsonl
"""
import argparse
import json
import math
import random

KINDS = ["plane", "sphere", "cylinder", "cone"]


def quaternion(rng):
    q = [rng.gauss(0, 1) for _ in range(4)]
    n = math.sqrt(sum(c * c for c in q))
    return [c / n for c in q]


def surface(rng, kind):
    centre = [rng.uniform(-1, 1) for _ in range(3)]
    rot = {"quaternion": quaternion(rng)}
    if kind == "plane":
        n = quaternion(rng)[:3]
        d = sum(a * b for a, b in zip(n, centre))
        return f"{n[0]!r}*x + {n[1]!r}*y + {n[2]!r}*z = {d!r}"
    if kind == "sphere":
        return {"type": "sphere", "center": centre, "radius": rng.uniform(0.3, 1)}
    if kind == "cylinder":
        return {"type": "cylinder", "center": centre, "radius": rng.uniform(0.3, 1),
                "rotation": rot}
    slope = rng.uniform(0.5, 2)  # x^2 + y^2 = (slope z)^2
    return {"type": "cone", "center": centre, "radii": [1.0, 1.0, 1.0 / slope], "rotation": rot}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--count", type=int, default=300)
    ap.add_argument("--seed", type=int, default=28)
    ap.add_argument("--kinds", default="")
    args = ap.parse_args()
    rng = random.Random(args.seed)
    n = 0
    while n < args.count:
        k1, k2 = rng.choice(KINDS), rng.choice(KINDS)
        if k1 == "plane" and k2 == "plane":
            continue
        if args.kinds and "-".join(sorted([k1, k2])) != "-".join(sorted(args.kinds.split("-"))):
            continue
        line = {"id": n, "op": "intersect", "a": surface(rng, k1), "b": surface(rng, k2),
                "label": f"{k1}-{k2}"}
        print(json.dumps(line))
        n += 1


if __name__ == "__main__":
    main()
