#!/usr/bin/env python3
"""Given boxes for generated pairs: each batch line of `surfcert generate` (op intersect) posed
in random axis-aligned boxes, the way an engineer hands a region to `intersect`.

  surfcert generate --case all --count 20 --seed 32 --encoding exact \
    | sed 's/"op":"classify"/"op":"intersect"/' > gen.jsonl
  python3 bench/boxed_pairs.py gen.jsonl --boxes 3 --seed 4 > boxed.jsonl
  surfcert batch --threads 2 < boxed.jsonl > answers.jsonl
  python3 bench/boxed_pairs.py --summary answers.jsonl
  python3 bench/check_pictures_exact.py boxed.jsonl answers.jsonl

Boxes: half-width h drawn from {0.01, 0.3, 1, 4, 20, 300, 10^4}, each side scaled by a factor in
[0.5, 1.5], centred at a uniform point of [-4, 4]^3 (generated curves live at unit scale near
the origin). The summary counts answers certified with a matching picture, and groups the
others by their note (numbers blanked), coincident pairs apart.
"""
import argparse
import collections
import json
import random
import re
import sys


def boxes(src, count, seed, out):
    rng = random.Random(seed)
    for line in open(src):
        d = json.loads(line)
        for k in range(count):
            h = rng.choice([0.01, 0.3, 1, 4, 20, 300, 1e4])
            c = [rng.uniform(-4, 4) for _ in range(3)]
            e = dict(d)
            e["id"] = "%s-b%d" % (d["id"], k)
            e["box"] = {"min": [x - h * rng.uniform(0.5, 1.5) for x in c],
                        "max": [x + h * rng.uniform(0.5, 1.5) for x in c]}
            out.write(json.dumps(e) + "\n")


def summary(answers):
    total = collections.Counter()
    notes = collections.Counter()
    first = {}
    for line in open(answers):
        d = json.loads(line)
        r = d.get("result", {})
        ok = d.get("status") == "certified" and r.get("branches_match_topology") is True
        coincident = r.get("morphology") == "coincident_quadrics"
        total["certified" if ok else "coincident" if coincident else "other"] += 1
        if ok or coincident:
            continue
        n = re.sub(r"[0-9][0-9.e+-]*", "N", d.get("note") or d.get("error") or "")[:110]
        notes[n] += 1
        first.setdefault(n, d.get("id"))
    print(json.dumps(dict(total)))
    for n, c in notes.most_common():
        print("%5d  %s  (e.g. %s)" % (c, n, first[n]))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("lines", nargs="?", help="generated batch lines (op intersect)")
    ap.add_argument("--boxes", type=int, default=3)
    ap.add_argument("--seed", type=int, default=4)
    ap.add_argument("--summary", metavar="ANSWERS", help="summarise a batch's answers instead")
    a = ap.parse_args()
    if a.summary:
        summary(a.summary)
    elif a.lines:
        boxes(a.lines, a.boxes, a.seed, sys.stdout)
    else:
        ap.error("give generated lines, or --summary ANSWERS")


if __name__ == "__main__":
    main()
