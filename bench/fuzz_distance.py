#!/usr/bin/env python3
"""Random quadric pairs (ten kinds, random rational rigid motions) through `surfcert distance
--json` in the filtered and the exact modes. Checks every certified answer against routes that
share nothing with it: the pair points lie on both surfaces and realise the distance; points
sampled on both surfaces (random lines, float) are never closer than the certified lower
bound; the two modes overlap. Usage: bench/fuzz_distance.py build/app/surfcert N SEED [-v]
[--degenerate] (-v lists the undecided pairs; --degenerate draws degenerate pencils only:
cylinders of any kind with one ruling direction, and cones with one apex). Prints the status
counts and the number of violations."""
import json, random, subprocess, sys, math
from fractions import Fraction as F

BIN = sys.argv[1]
N = int(sys.argv[2]) if len(sys.argv) > 2 else 50
random.seed(int(sys.argv[3]) if len(sys.argv) > 3 else 1)

KINDS = {
    'ellipsoid': lambda a, b, c: [[1/a, 0, 0, 0], [0, 1/b, 0, 0], [0, 0, 1/c, 0], [0, 0, 0, -1]],
    'hyp1': lambda a, b, c: [[1/a, 0, 0, 0], [0, 1/b, 0, 0], [0, 0, -1/c, 0], [0, 0, 0, -1]],
    'hyp2': lambda a, b, c: [[1/a, 0, 0, 0], [0, 1/b, 0, 0], [0, 0, -1/c, 0], [0, 0, 0, 1]],
    'cone': lambda a, b, c: [[1/a, 0, 0, 0], [0, 1/b, 0, 0], [0, 0, -1/c, 0], [0, 0, 0, 0]],
    'cyl': lambda a, b, c: [[1/a, 0, 0, 0], [0, 1/b, 0, 0], [0, 0, 0, 0], [0, 0, 0, -1]],
    'par': lambda a, b, c: [[1/a, 0, 0, 0], [0, 1/b, 0, 0], [0, 0, 0, F(-1, 2)], [0, 0, F(-1, 2), 0]],
    'hpar': lambda a, b, c: [[1/a, 0, 0, 0], [0, -1/b, 0, 0], [0, 0, 0, F(-1, 2)], [0, 0, F(-1, 2), 0]],
    'plane': lambda a, b, c: [[0, 0, 0, 0], [0, 0, 0, 0], [0, 0, 0, F(1, 2)], [0, 0, F(1, 2), 0]],
    'hcyl': lambda a, b, c: [[1/a, 0, 0, 0], [0, -1/b, 0, 0], [0, 0, 0, 0], [0, 0, 0, -1]],
    'pcyl': lambda a, b, c: [[1/a, 0, 0, 0], [0, 0, 0, 0], [0, 0, 0, F(-1, 2)], [0, 0, F(-1, 2), 0]],
}
# Parabolic cylinder ruled along z like cyl and hcyl (x^2 / a = y), for the degenerate draws.
PCYLZ = lambda a, b, c: [[1/a, 0, 0, 0], [0, 0, 0, F(-1, 2)], [0, 0, 0, 0], [0, F(-1, 2), 0, 0]]
DEGENERATE = '--degenerate' in sys.argv


def rot(w, x, y, z):
    n = w*w + x*x + y*y + z*z
    R = [[w*w+x*x-y*y-z*z, 2*(x*y-w*z), 2*(x*z+w*y)],
         [2*(x*y+w*z), w*w-x*x+y*y-z*z, 2*(y*z-w*x)],
         [2*(x*z-w*y), 2*(y*z+w*x), w*w-x*x-y*y+z*z]]
    return [[F(R[i][j], n) for j in range(3)] for i in range(3)]


def random_rotation():
    qq = [random.randint(-3, 3) for _ in range(4)]
    if not any(qq) or random.random() >= 0.7:
        qq = [1, 0, 0, 0]
    return qq


def random_translation():
    return [F(random.randint(-12, 12), random.randint(1, 3)) for _ in range(3)]


def random_quadric(kind, qq=None, t=None):
    a, b, c = (F(random.randint(1, 9), random.randint(1, 4)) for _ in range(3))
    M = [[F(v) for v in row] for row in (PCYLZ if kind == 'pcylz' else KINDS[kind])(a, b, c)]
    R = rot(*(qq or random_rotation()))
    t = t or random_translation()
    # x' = R^T (x - t): T maps x to local coordinates; Q' = T^T M T, T = [[R^T, -R^T t], [0, 1]]
    T = [[R[j][i] for j in range(3)] + [-sum(R[j][i]*t[j] for j in range(3))] for i in range(3)]
    T.append([F(0), F(0), F(0), F(1)])
    MT = [[sum(M[i][k]*T[k][j] for k in range(4)) for j in range(4)] for i in range(4)]
    Q = [[sum(T[k][i]*MT[k][j] for k in range(4)) for j in range(4)] for i in range(4)]
    return Q


def equation(Q):
    v = ['x', 'y', 'z', '1']
    terms = []
    for i in range(4):
        for j in range(i, 4):
            c = Q[i][j] * (1 if i == j else 2)
            if c == 0:
                continue
            mon = '*'.join(s for s in (v[i], v[j]) if s != '1') or '1'
            terms.append(f"({c})*{mon}")
    return ' + '.join(terms) + ' = 0'


def qval(Q, p):
    X = [p[0], p[1], p[2], 1.0]
    return sum(float(Q[i][j]) * X[i] * X[j] for i in range(4) for j in range(4))


def samples(Q, n, box):
    pts = []
    tries = 0
    while len(pts) < n and tries < 50 * n:
        tries += 1
        o = [random.uniform(-box, box) for _ in range(3)]
        d = [random.gauss(0, 1) for _ in range(3)]
        # Q(o + s d) = A s^2 + B s + C
        f0 = qval(Q, o)
        f1 = qval(Q, [o[k] + d[k] for k in range(3)])
        fm = qval(Q, [o[k] - d[k] for k in range(3)])
        A = (f1 + fm) / 2 - f0
        B = (f1 - fm) / 2
        if abs(A) < 1e-14:
            if abs(B) > 1e-14:
                s = -f0 / B
                pts.append([o[k] + s*d[k] for k in range(3)])
            continue
        D = B*B - 4*A*f0
        if D < 0:
            continue
        for sg in (-1, 1):
            s = (-B + sg*math.sqrt(D)) / (2*A)
            pts.append([o[k] + s*d[k] for k in range(3)])
    return pts


def run(a, b, mode):
    out = subprocess.run([BIN, 'distance', a, b, '--mode', mode, '--json'], capture_output=True,
                         text=True, timeout=120)
    try:
        return json.loads(out.stdout)
    except Exception:
        return {'status': 'crash', 'note': out.stderr[-300:]}


bad = 0
stats = {}
for k in range(N):
    if DEGENERATE and k % 2 == 0:  # one ruling direction: the same rotation
        ka, kb = (random.choice(['cyl', 'hcyl', 'pcylz']) for _ in range(2))
        qq = random_rotation()
        Qa, Qb = random_quadric(ka, qq=qq), random_quadric(kb, qq=qq)
    elif DEGENERATE:  # one apex: the same translation
        ka, kb = 'cone', 'cone'
        t = random_translation()
        Qa, Qb = random_quadric(ka, t=t), random_quadric(kb, t=t)
    else:
        ka, kb = random.choice(list(KINDS)), random.choice(list(KINDS))
        Qa, Qb = random_quadric(ka), random_quadric(kb)
    ea, eb = equation(Qa), equation(Qb)
    res = {}
    for mode in ('filtered', 'exact'):
        try:
            res[mode] = run(ea, eb, mode)
        except subprocess.TimeoutExpired:
            res[mode] = {'status': 'timeout'}
    key = f"{ka}-{kb}"
    st = tuple(res[m]['status'] for m in ('filtered', 'exact'))
    if '-v' in sys.argv and res['filtered'].get('status') != 'certified':
        print('UNDECIDED', key, res['filtered'].get('note', '')[:150], '::', ea, '|', eb)
    stats.setdefault(st, 0)
    stats[st] += 1
    pa = samples(Qa, 500, 30)
    pb = samples(Qb, 500, 30)
    smin = min((math.dist(p, q) for p in pa for q in pb), default=float('inf'))
    for mode, r in res.items():
        if r.get('status') == 'crash':
            print('CRASH', key, mode, r['note'], ea, '|', eb)
            bad += 1
            continue
        if r.get('status') != 'certified':
            continue
        d = r['result']['distance']
        lo, up = float(d['lower']), float(d['upper'])
        if smin < lo - 1e-9 * (1 + lo):
            print('LOWER BOUND VIOLATED', key, mode, lo, smin, r['result'].get('method'), ea, '|', eb)
            bad += 1
        for pr in r['result']['pairs']:
            p, q = pr
            sc = 1 + max(abs(x) for x in p + q)
            if abs(qval(Qa, p)) > 1e-6 * sc * sc or abs(qval(Qb, q)) > 1e-6 * sc * sc:
                print('PAIR OFF SURFACE', key, mode, r['result'].get('method'), p, q, qval(Qa, p), qval(Qb, q), ea, '|', eb)
                bad += 1
            if r['result']['minimizers'] != '0' and abs(math.dist(p, q) - float(d['approx'])) > 1e-6 * sc:
                print('PAIR DISTANCE', key, mode, r['result'].get('method'), math.dist(p, q), d['approx'], ea, '|', eb)
                bad += 1
    if all(res[m].get('status') == 'certified' for m in res):
        l1, u1 = float(res['filtered']['result']['distance']['lower']), float(res['filtered']['result']['distance']['upper'])
        l2, u2 = float(res['exact']['result']['distance']['lower']), float(res['exact']['result']['distance']['upper'])
        if l1 > u2 * (1 + 1e-12) + 1e-300 or l2 > u1 * (1 + 1e-12) + 1e-300:
            print('MODES DISAGREE', key, l1, u1, l2, u2, ea, '|', eb)
            bad += 1
    sys.stderr.write(f"\r{k+1}/{N} bad={bad}")
print()
print('status (filtered, exact) counts:', stats)
print('bad:', bad)
sys.exit(1 if bad else 0)
