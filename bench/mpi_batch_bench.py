#!/usr/bin/env python3
"""`surfcert batch --mpi` figures (bench/results/mpi_batch.md): lines per second with 1, 2 and 4
ranks against the single-process batch, and a heavy-tailed workload (a few budget-limited slow
lines among many fast ones) scheduled on demand (batch --mpi) against a static split of the file
(the file cut in W contiguous parts, one single-process batch per part, all at once: what a user
without MPI does). Wall times of whole processes (mpirun's start included; its cost alone, on an
empty input, is printed too). Only the standard library.

usage: mpi_batch_bench.py SURFCERT [--fast N] [--medium N] [--slow K] [--slow-ms MS] [--repeat R]
"""
import argparse
import os
import random
import resource
import shutil
import subprocess
import tempfile
import time

MPIRUN = shutil.which("mpirun") or "mpirun"


def mpirun(n):
    return [MPIRUN, "--allow-run-as-root", "--oversubscribe", "-n", str(n)]


def cpu_children():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def run_timed(cmd, stdin_path):
    """(wall seconds, CPU seconds of every process of the run) of cmd, stdin from stdin_path."""
    with open(stdin_path, "rb") as f:
        c0 = cpu_children()
        t0 = time.perf_counter()
        p = subprocess.run(cmd, stdin=f, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        t = time.perf_counter() - t0
        c = cpu_children() - c0
    if p.returncode not in (0, 3):
        raise SystemExit("failed (%d): %s\n%s" % (p.returncode, " ".join(cmd), p.stderr.decode()))
    return t, c


def wall(cmd, stdin_path):
    return run_timed(cmd, stdin_path)[0]


def best(cmd, path, repeat):
    return min(wall(cmd, path) for _ in range(repeat))


def best_pair(cmd, path, repeat):
    """The run of least wall time: (wall, cpu)."""
    return min(run_timed(cmd, path) for _ in range(repeat))


def static_split(binary, lines, parts, tmp):
    """Wall time of `parts` single-process batches at once, each on a contiguous part."""
    n = len(lines)
    paths = []
    for k in range(parts):
        p = os.path.join(tmp, "part%d.jsonl" % k)
        with open(p, "w") as f:
            f.writelines(lines[k * n // parts:(k + 1) * n // parts])
        paths.append(p)
    t0 = time.perf_counter()
    procs = [subprocess.Popen([binary, "batch"], stdin=open(p, "rb"), stdout=subprocess.DEVNULL,
                              stderr=subprocess.DEVNULL) for p in paths]
    for pr in procs:
        pr.wait()
    return time.perf_counter() - t0


def slow_line(i, budget_ms):
    # Two tori 1e-20 apart: minutes of branch and bound, so always `budget_ms` then undecided.
    return ('{"id":"slow%d","op":"distance","a":{"type":"torus","center":[0,0,0],"axis":[0,0,1],'
            '"major_radius":3,"minor_radius":1},"b":{"type":"torus","center":'
            '["799999999999999999999/100000000000000000000",0,0],"axis":[0,0,1],'
            '"major_radius":3,"minor_radius":1},"budget_ms":%d}\n' % (i, budget_ms))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("surfcert")
    ap.add_argument("--fast", type=int, default=20, help="classify lines per case (x37 cases)")
    ap.add_argument("--medium", type=int, default=40, help="distance lines per case (x3 cases)")
    ap.add_argument("--slow", type=int, default=6, help="slow lines in the heavy-tailed file")
    ap.add_argument("--slow-ms", type=int, default=1500, help="their budget")
    ap.add_argument("--repeat", type=int, default=2, help="runs per figure (the best is kept)")
    a = ap.parse_args()
    b = a.surfcert
    tmp = tempfile.mkdtemp(prefix="mpi_bench_")
    load = os.getloadavg()
    print("machine: nproc %d, load average %.2f %.2f %.2f" % (os.cpu_count(), *load))

    def gen(args, name):
        p = os.path.join(tmp, name)
        with open(p, "w") as f:
            subprocess.run([b, "generate"] + args, stdout=f, check=True)
        with open(p) as f:
            return p, f.readlines()

    fast_p, fast = gen(["--case", "all", "--count", str(a.fast), "--seed", "1",
                        "--encoding", "double"], "fast.jsonl")
    med_p, med = gen(["--case", "distance", "--count", str(a.medium), "--seed", "2"],
                     "medium.jsonl")
    empty = os.path.join(tmp, "empty.jsonl")
    open(empty, "w").close()
    start = {n: best(mpirun(n) + [b, "batch", "--mpi"], empty, a.repeat) for n in (1, 2, 3, 4)}
    print("mpirun start and end alone (empty input): " +
          ", ".join("%d ranks %.2f s" % (n, t) for n, t in start.items()))

    print("\nthroughput: lines/s over the whole run's wall time (in brackets: over the wall time"
          " minus mpirun's start and end alone). Ranks beyond 2 are oversubscribed (2 cores);"
          " rank 0 schedules, ranks 1.. compute with --threads 1; -n 1: rank 0 computes.")
    print("CPU: milliseconds of CPU (every process of the run, mpirun included) per line.")
    print("%-34s %9s (%6s) %7s %9s (%6s) %7s" % ("", "classify", "net", "CPU ms", "distance",
                                                "net", "CPU ms"))
    print("%-34s %9d %16d" % ("lines", len(fast), len(med)))
    rows = [("single-process batch --threads 1", [b, "batch", "--threads", "1"], 0),
            ("single-process batch --threads 2", [b, "batch", "--threads", "2"], 0)]
    for n in (1, 2, 4):
        rows.append(("mpirun -n %d batch --mpi" % n, mpirun(n) + [b, "batch", "--mpi"], start[n]))
    for label, cmd, s0 in rows:
        t1, c1 = best_pair(cmd, fast_p, a.repeat)
        t2, c2 = best_pair(cmd, med_p, a.repeat)
        net = lambda n, t: "%6.0f" % (n / (t - s0)) if s0 and t > s0 else "     -"
        print("%-34s %9.0f (%s) %7.2f %9.1f (%s) %7.1f" % (
            label, len(fast) / t1, net(len(fast), t1), 1000 * c1 / len(fast),
            len(med) / t2, net(len(med), t2), 1000 * c2 / len(med)))

    # Heavy tail: the distance lines with a few slow lines, at random places, then together (a
    # file sorted by case: the slow ones in one part of a static split).
    rnd = random.Random(7)
    spread = list(med)
    for i in range(a.slow):
        spread.insert(rnd.randrange(len(spread) + 1), slow_line(i, a.slow_ms))
    middle = len(med) // 3
    together = med[:middle] + [slow_line(i, a.slow_ms) for i in range(a.slow)] + med[middle:]
    print("\nheavy tail: %d distance lines + %d lines of budget %d ms (two tori 1e-20 apart;"
          " a budget overshoots by up to one uninterruptible step: seconds under load)"
          % (len(med), a.slow, a.slow_ms))
    for name, tail in (("at random places", spread), ("together", together)):
        tail_p = os.path.join(tmp, "tail.jsonl")
        with open(tail_p, "w") as f:
            f.writelines(tail)
        print(" slow lines %s:" % name)
        for w in (2, 3):
            per = [sum(1 for l in tail[k * len(tail) // w:(k + 1) * len(tail) // w]
                       if '"slow' in l) for k in range(w)]
            ts = min(static_split(b, tail, w, tmp) for _ in range(a.repeat))
            td = best(mpirun(w + 1) + [b, "batch", "--mpi"], tail_p, a.repeat)
            print("  %d workers: static split %6.2f s (slow lines per part %s); dynamic"
                  " (mpirun -n %d) %6.2f s, %6.2f s without mpirun's start and end"
                  % (w, ts, per, w + 1, td, td - start[w + 1]))
    print("load average after: %.2f %.2f %.2f" % os.getloadavg())
    shutil.rmtree(tmp)


if __name__ == "__main__":
    main()
