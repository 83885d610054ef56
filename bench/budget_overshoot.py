#!/usr/bin/env python3
"""How far past its `budget_ms` a query runs (bench/results/budget_overshoot.md).

Each line of a corpus of slow queries (bench/budget_corpus.jsonl: tori 1e-20 apart, nested
ellipsoids in exact mode, an implicit quartic 1e-20 from a sphere, a parametric and a sextic
surface, plus fast lines as a control) is sent with "budget_ms": B for each budget B, through
`surfcert batch --threads 1`, R times; the figure is each answer's own `time_ms` (the wall time
of the line) over B. A query the budget stopped answers undecided with reason "budget"; one
that finished first answers as without a budget. The load average is printed: on a shared
machine a line's wall time grows with the load while its budget does not, so read the ratios
with it.

usage: budget_overshoot.py SURFCERT [--corpus FILE] [--budgets 10,50,200] [--repeat R]
"""
import argparse
import json
import os
import platform
import subprocess
import time


def run(surfcert, lines, budget):
    text = "".join(json.dumps(dict(json.loads(l), budget_ms=budget)) + "\n" for l in lines)
    p = subprocess.run([surfcert, "batch", "--threads", "1"], input=text.encode(),
                       stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, check=False)
    return [json.loads(l) for l in p.stdout.decode().splitlines() if l.strip()]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("surfcert")
    here = os.path.dirname(os.path.abspath(__file__))
    ap.add_argument("--corpus", default=os.path.join(here, "budget_corpus.jsonl"))
    ap.add_argument("--budgets", default="10,50,200")
    ap.add_argument("--repeat", type=int, default=3)
    a = ap.parse_args()
    lines = [l for l in open(a.corpus) if l.strip()]
    budgets = [float(b) for b in a.budgets.split(",")]
    print("# budget overshoot: `time_ms` / `budget_ms` per line\n")
    print("Machine: %s, %d cores; %s UTC; load average at start %s. surfcert: %s; corpus %s "
          "(%d lines), %d runs per budget, `batch --threads 1`.\n" %
          (platform.processor() or platform.machine(), os.cpu_count(),
           time.strftime("%Y-%m-%d %H:%M", time.gmtime()),
           " ".join("%.2f" % x for x in os.getloadavg()), a.surfcert,
           os.path.basename(a.corpus), len(lines), a.repeat))
    print("| line | budget ms | status (reason) | max time_ms | max time_ms / budget |")
    print("|---|---|---|---|---|")
    worst = {}
    for b in budgets:
        per = {}
        for _ in range(a.repeat):
            for ans in run(a.surfcert, lines, b):
                key = ans.get("id")
                st = ans.get("status", "?") + (" (%s)" % ans["reason"] if "reason" in ans else "")
                t = float(ans.get("time_ms", 0))
                prev = per.get(key)
                if prev is None or t > prev[1]:
                    per[key] = (st, t)
        for key, (st, t) in per.items():
            print("| %s | %g | %s | %.1f | %.2f |" % (key, b, st, t, t / b))
            if "budget" in st:
                worst[b] = max(worst.get(b, 0), t / b)
    print("\nLoad average at the end: %s." % " ".join("%.2f" % x for x in os.getloadavg()))
    for b in budgets:
        print("Budget %g ms: the worst budget-stopped line took %.2f x its budget." %
              (b, worst.get(b, 0)))


if __name__ == "__main__":
    main()
