#!/usr/bin/env python3
"""Random tori and capsules against random quadrics and against each other, through
`surfcert distance --json` (filtered and exact modes). Every certified answer is checked against
routes that share nothing with it: points sampled on both surfaces (float) are never closer
than the certified lower bound, the reported pair points lie on both surfaces and realise the
distance, and the two modes overlap. Usage:
  bench/fuzz_shapes.py build/app/surfcert N SEED [-v]
Prints the status counts and the number of violations (exit status 1 if any)."""
import json, math, random, subprocess, sys
from fractions import Fraction as F

BIN = sys.argv[1]
N = int(sys.argv[2]) if len(sys.argv) > 2 else 30
random.seed(int(sys.argv[3]) if len(sys.argv) > 3 else 1)
VERBOSE = '-v' in sys.argv


def rand_vec(lo, hi):
    return [random.randint(lo, hi) for _ in range(3)]


def torus():
    a = rand_vec(-3, 3)
    while a == [0, 0, 0]:
        a = rand_vec(-3, 3)
    R = F(random.randint(4, 12), 2)
    r = F(random.randint(1, int(R * 2) - 1), 4)
    c = [F(random.randint(-20, 20), 2) for _ in range(3)]
    js = {"type": "torus", "center": [str(x) for x in c], "axis": a,
          "major_radius": str(R), "minor_radius": str(r)}
    return ('torus', js, (c, a, R, r))


def capsule():
    p = [F(random.randint(-20, 20), 2) for _ in range(3)]
    q = [x + random.randint(-6, 6) for x in p]
    if q == p:
        q[0] += 1
    r = F(random.randint(1, 6), 4)
    js = {"type": "capsule", "from": [str(x) for x in p], "to": [str(x) for x in q],
          "radius": str(r)}
    return ('capsule', js, (p, q, r))


def ellipsoid():
    c = [random.randint(-10, 10) for _ in range(3)]
    ax = [random.randint(1, 5) for _ in range(3)]
    eq = ' + '.join(f"(({v}) - ({cc}))^2/{a * a}" for v, cc, a in zip('xyz', c, ax)) + ' = 1'
    return ('ellipsoid', eq, (c, ax))


def points(shape, n):
    kind, _, par = shape
    pts = []
    if kind == 'torus':
        c, a, R, r = par
        an = math.sqrt(sum(x * x for x in a))
        n_ = [x / an for x in a]
        e = [0, 0, 0]
        e[min(range(3), key=lambda i: abs(n_[i]))] = 1
        u = [n_[1] * e[2] - n_[2] * e[1], n_[2] * e[0] - n_[0] * e[2], n_[0] * e[1] - n_[1] * e[0]]
        un = math.sqrt(sum(x * x for x in u))
        u = [x / un for x in u]
        v = [n_[1] * u[2] - n_[2] * u[1], n_[2] * u[0] - n_[0] * u[2], n_[0] * u[1] - n_[1] * u[0]]
        for i in range(n):
            for j in range(n // 2):
                t, p = 2 * math.pi * i / n, 2 * math.pi * j / (n // 2)
                rho = float(R) + float(r) * math.cos(p)
                pts.append([float(c[k]) + rho * (math.cos(t) * u[k] + math.sin(t) * v[k]) +
                            float(r) * math.sin(p) * n_[k] for k in range(3)])
    elif kind == 'capsule':  # the side (normals orthogonal to the spine) and the two caps
        p, q, r = par
        ax = [float(q[k] - p[k]) for k in range(3)]
        L = math.sqrt(sum(x * x for x in ax))
        ax = [x / L for x in ax]
        for i in range(n * n // 2):
            d = [random.gauss(0, 1) for _ in range(3)]
            t = sum(d[k] * ax[k] for k in range(3))
            s = random.random()
            if i % 3 == 0:  # side: remove the axial part
                d = [d[k] - t * ax[k] for k in range(3)]
            dn = math.sqrt(sum(x * x for x in d))
            t = sum(d[k] * ax[k] for k in range(3)) / dn
            end = p if t < 0 else q
            base = ([float(p[k]) + s * float(q[k] - p[k]) for k in range(3)] if i % 3 == 0
                    else [float(x) for x in end])
            pts.append([base[k] + float(r) * d[k] / dn for k in range(3)])
    else:
        c, ax = par
        for i in range(n * n // 2):
            d = [random.gauss(0, 1) for _ in range(3)]
            dn = math.sqrt(sum(x * x for x in d))
            pts.append([c[k] + ax[k] * d[k] / dn for k in range(3)])
    return pts


def on_surface(shape, x):
    kind, _, par = shape
    if kind == 'torus':
        c, a, R, r = par
        w = [x[k] - float(c[k]) for k in range(3)]
        an = math.sqrt(sum(v * v for v in a))
        h = sum(w[k] * a[k] for k in range(3)) / an
        rho = math.sqrt(max(0.0, sum(v * v for v in w) - h * h))
        return abs(math.hypot(rho - float(R), h) - float(r))
    if kind == 'capsule':
        p, q, r = par
        d = [float(q[k] - p[k]) for k in range(3)]
        w = [x[k] - float(p[k]) for k in range(3)]
        t = max(0.0, min(1.0, sum(w[k] * d[k] for k in range(3)) / sum(v * v for v in d)))
        return abs(math.dist(x, [float(p[k]) + t * d[k] for k in range(3)]) - float(r))
    c, ax = par
    return abs(math.sqrt(sum(((x[k] - c[k]) / ax[k]) ** 2 for k in range(3))) - 1) * min(ax)


def arg(shape):
    kind, js, _ = shape
    return js if isinstance(js, str) else json.dumps(js)


def run(a, b, mode):
    out = subprocess.run([BIN, 'distance', arg(a), arg(b), '--mode', mode, '--json'],
                         capture_output=True, text=True, timeout=300)
    try:
        return json.loads(out.stdout)
    except Exception:
        return {'status': 'crash', 'note': out.stderr[-300:]}


bad, stats = 0, {}
makers = [torus, capsule, ellipsoid]
for k in range(N):
    a = random.choice(makers[:2])()
    b = random.choice(makers)()
    res = {m: run(a, b, m) for m in ('filtered', 'exact')}
    key = f"{a[0]}-{b[0]}"
    st = (key,) + tuple(res[m]['status'] for m in res)
    stats[st] = stats.get(st, 0) + 1
    if VERBOSE and res['filtered'].get('status') != 'certified':
        print('UNDECIDED', key, res['filtered'].get('note', '')[:160])
    pa, pb = points(a, 60), points(b, 60)
    smin = min(math.dist(p, q) for p in pa for q in pb)
    for mode, r in res.items():
        if r.get('status') == 'crash':
            print('CRASH', key, mode, r['note'], arg(a), arg(b))
            bad += 1
            continue
        if r.get('status') != 'certified':
            continue
        d = r['result']['distance']
        lo = float(d['lower'])
        if smin < lo - 1e-9 * (1 + lo):
            print('LOWER BOUND VIOLATED', key, mode, lo, smin, r['result'].get('method'),
                  arg(a), arg(b))
            bad += 1
        for p, q in r['result']['pairs']:
            sc = 1 + max(abs(x) for x in p + q)
            if on_surface(a, p) > 1e-6 * sc or on_surface(b, q) > 1e-6 * sc:
                print('PAIR OFF SURFACE', key, mode, r['result'].get('method'), p, q,
                      on_surface(a, p), on_surface(b, q), arg(a), arg(b))
                bad += 1
    if all(res[m].get('status') == 'certified' for m in res):
        l1, u1 = (float(res['filtered']['result']['distance'][x]) for x in ('lower', 'upper'))
        l2, u2 = (float(res['exact']['result']['distance'][x]) for x in ('lower', 'upper'))
        if l1 > u2 * (1 + 1e-12) or l2 > u1 * (1 + 1e-12):
            print('MODES DISAGREE', key, l1, u1, l2, u2, arg(a), arg(b))
            bad += 1
    sys.stderr.write(f"\r{k + 1}/{N} bad={bad}")
print()
for s in sorted(stats):
    print(s, stats[s])
print('bad:', bad)
sys.exit(1 if bad else 0)
