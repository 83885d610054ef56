#!/usr/bin/env python3
"""Same-run A/B of two surfcert binaries on one JSONL batch, whole process.

Usage: python3 bench/ab_batch.py FILE.jsonl OLD_BIN NEW_BIN [RUNS=11] [THREADS=1]

Runs `BIN batch --threads THREADS < FILE` for OLD and NEW alternately, RUNS times each (stdout
discarded), and prints the fastest and median wall time of each and the ratios old/new: ratio
of medians, of the fastest runs, and the median of the ratios of runs side by side. Alternating
in one run is what makes the ratio meaningful on a shared machine whose speed drifts.
"""
import statistics
import subprocess
import sys
import time


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    path, old, new = sys.argv[1:4]
    runs = int(sys.argv[4]) if len(sys.argv) > 4 else 11
    threads = sys.argv[5] if len(sys.argv) > 5 else "1"
    times = {old: [], new: []}
    for _ in range(runs):
        for b in (old, new):
            with open(path) as f:
                t0 = time.perf_counter()
                subprocess.run([b, "batch", "--threads", threads], stdin=f,
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=False)
                times[b].append(time.perf_counter() - t0)
    for name, b in (("old", old), ("new", new)):
        t = times[b]
        print(f"{name} {b}: fastest {min(t) * 1e3:.1f} ms, median {statistics.median(t) * 1e3:.1f} ms")
    a, c = times[old], times[new]
    print("old/new: ratio of medians %.2f, of fastest %.2f, median of paired ratios %.2f" %
          (statistics.median(a) / statistics.median(c), min(a) / min(c),
           statistics.median([x / y for x, y in zip(a, c)])))


if __name__ == "__main__":
    main()
