#!/usr/bin/env python3
"""Pipes and cones posed as a user's program poses them: the matrix M^T Q M computed in double
(plain Python floats, not symmetrised afterwards), as a `surfcert batch` JSONL file for
whole-process runs (bench/ab_batch.py, or `surfcert batch --threads 1 < file`).

Families (each under `--count` uniformly random rotations, Gaussian translations): Steinmetz
(two unit cylinders, axes crossing), pipes tangent inside (radius 1 and 1/2, axis offset 1/2),
a T-junction (radius 1 and 1/2), a cone and a cylinder through its apex (tangent), a cone and a
coaxial cylinder. Rounded, the singular pencils of the first two become smooth curves with
necks ~1e-8 wide (one or two ovals, decided exactly by surfcert); every line carries its
family in "label".

Usage: pipes_as_matrices.py [--count 40] [--seed 29] > pipes.jsonl
"""
import argparse
import json
import math
import random


def rotation(rng):
    q = [rng.gauss(0, 1) for _ in range(4)]
    n = math.sqrt(sum(c * c for c in q))
    w, x, y, z = (c / n for c in q)
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]


def matmul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def cylinder(axis, r=1.0, c=(0.0, 0.0, 0.0)):
    m = [[0.0] * 4 for _ in range(4)]
    for k in range(3):
        if k == axis:
            continue
        m[k][k] = 1.0
        m[k][3] = m[3][k] = -c[k]
        m[3][3] += c[k] * c[k]
    m[3][3] -= r * r
    return m


def cone(axis, c=(0.0, 0.0, 0.0)):
    m = [[0.0] * 4 for _ in range(4)]
    for k in range(3):
        s = -1.0 if k == axis else 1.0
        m[k][k] = s
        m[k][3] = m[3][k] = -s * c[k]
        m[3][3] += s * c[k] * c[k]
    return m


FAMILIES = {
    "steinmetz": (cylinder(2), cylinder(0)),
    "tangent_pipes": (cylinder(2), cylinder(1, 0.5, (0.5, 0.0, 0.0))),
    "t_junction": (cylinder(2), cylinder(0, 0.5)),
    "cone_cylinder_tangent": (cone(2), cylinder(2, 1.0, (1.0, 0.0, 0.0))),
    "cone_cylinder_coaxial": (cone(2), cylinder(2)),
}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--count", type=int, default=40)
    ap.add_argument("--seed", type=int, default=29)
    args = ap.parse_args()
    rng = random.Random(args.seed)
    line = 0
    for name, (qa, qb) in FAMILIES.items():
        for _ in range(args.count):
            r = rotation(rng)
            t = [rng.gauss(0, 1) for _ in range(3)]
            # x_local = R^T (x - t): M = [R^T, -R^T t; 0, 1]
            m = [[r[j][i] for j in range(3)] + [-sum(r[k][i] * t[k] for k in range(3))]
                 for i in range(3)] + [[0.0, 0.0, 0.0, 1.0]]
            mt = [[m[j][i] for j in range(4)] for i in range(4)]
            pa, pb = matmul(mt, matmul(qa, m)), matmul(mt, matmul(qb, m))
            print(json.dumps({"id": line, "label": name, "op": "intersect", "detail": "topology",
                              "a": {"matrix": pa}, "b": {"matrix": pb}}))
            line += 1


if __name__ == "__main__":
    main()
