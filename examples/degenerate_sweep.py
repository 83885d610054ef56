#!/usr/bin/env python3
"""A degenerate sweep in the style of a notebook: two unit spheres whose gap is 2^-k,
k = 10..60, asked in the three modes. Where does plain floating point go wrong?

    PYTHONPATH=build/python /usr/bin/python3 examples/degenerate_sweep.py [out.png]

The second centre, (3/5, 4/5, 0) (2 + 2^-k), is given as exact Fractions (as doubles it would
be rounded). The exact answer is known in closed form: the spheres are separated, their
intersection is empty (two imaginary conics), the distance is 2^-k. Writes a PNG (matplotlib,
Agg backend) and prints the table it plots. An undecided answer (float mode may fail to tell
the roots apart and say so) carries no relation: it is shown as undecided, not as right or
wrong.
"""
import sys
from fractions import Fraction

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import surfcert  # noqa: E402

MODES = ("float", "filtered", "exact")
ks = list(range(10, 61))
unit = "x^2 + y^2 + z^2 = 1"
others = []
for k in ks:
    r = Fraction(2) + Fraction(1, 2**k)
    others.append({"type": "sphere", "center": [Fraction(3, 5) * r, Fraction(4, 5) * r, 0],
                   "radius": 1})

# 1. Classify: one batch per mode (native threads, the GIL released), topology only.
answers = {m: surfcert.classify_batch(unit, others, mode=m, detail="topology") for m in MODES}

# 2. Distance: the float estimate against the certified enclosure (which must hold 2^-k).
float_d = surfcert.distance_batch(unit, others, mode="float")
cert_d = surfcert.distance_batch(unit, others)



def relation(answer):
    """The answer's ellipsoid relation, or "undecided" when it proves none: an undecided answer
    (e.g. a float classify whose roots it could not tell apart) carries no relation, and saying
    so is the honest reading, neither right nor wrong."""
    if answer.status == "undecided":
        return "undecided"
    return answer.json["result"]["ellipsoid_relation"]


print(" k  float relation        filtered   exact      float distance rel. error  certified")
wrong, undecided, err = [], [], []
for i, k in enumerate(ks):
    truth = Fraction(1, 2**k)
    rel = {m: relation(answers[m][i]) for m in MODES}
    assert answers["exact"][i].status == "certified" and rel["exact"] == "separated"
    assert cert_d[i].status == "certified"
    d = cert_d[i].result.distance
    assert d.lower <= truth <= d.upper  # the proven enclosure holds the closed form
    est = float_d[i].result.get("estimate")
    e = abs(Fraction(est.value) - truth) / truth if est else Fraction(0)
    undecided.append([rel[m] == "undecided" for m in MODES])
    wrong.append([rel[m] not in (rel["exact"], "undecided") for m in MODES])
    err.append(float(e) if est else None)
    print(f"{k:2d}  {rel['float']:20s}  {rel['filtered']:9s}  {rel['exact']:9s}  "
          f"{float(e) if est else float('nan'):25.3g}  [{float(d.lower):.6g}, {float(d.upper):.6g}]"
          f"{'' if est else '  (float mode answered certified)'}")

first_wrong = next((k for k, w in zip(ks, wrong) if w[0]), None)
first_undecided = next((k for k, u in zip(ks, undecided) if u[0]), None)
print(f"float classify first wrong at k = {first_wrong}, first undecided at k = "
      f"{first_undecided} ({sum(u[0] for u in undecided)} undecided); filtered and exact "
      f"wrong: {sum(w[1] or w[2] for w in wrong)} of {len(ks)}, undecided: "
      f"{sum(u[1] or u[2] for u in undecided)}")

fig, (top, bottom) = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
for j, m in enumerate(MODES):
    ok = [k for k, w, u in zip(ks, wrong, undecided) if not w[j] and not u[j]]
    bad = [k for k, w in zip(ks, wrong) if w[j]]
    open_ = [k for k, u in zip(ks, undecided) if u[j]]
    top.scatter(ok, [j] * len(ok), marker="o", color="tab:green", s=18)
    top.scatter(bad, [j] * len(bad), marker="x", color="tab:red", s=30)
    top.scatter(open_, [j] * len(open_), marker="s", facecolors="none", color="tab:gray", s=22)
top.set_yticks(range(len(MODES)), [f"classify --mode {m}" for m in MODES])
top.set_title("two unit spheres at gap $2^{-k}$: relation (o right, x wrong, "
              "square undecided)", fontsize=10)
pts = [(k, e) for k, e in zip(ks, err) if e is not None and e > 0]
bottom.semilogy([k for k, _ in pts], [e for _, e in pts], "o-", ms=3,
                label="float distance estimate, relative error")
bottom.axhline(1e-15, color="tab:green", ls="--", label="certified enclosure: width <= 1e-15 rel.")
last = max((k for k, _ in pts), default=None)
bottom.set_title("distance: float estimate against the exact $2^{-k}$"
                 + (f" (none after k = {last})" if last is not None else ""), fontsize=10)
bottom.set_xlabel("k (gap $2^{-k}$)")
bottom.legend(fontsize=8)
fig.tight_layout()
out = sys.argv[1] if len(sys.argv) > 1 else "degenerate_sweep.png"
fig.savefig(out, dpi=110)
print("wrote", out)
