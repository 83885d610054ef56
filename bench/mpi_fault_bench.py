#!/usr/bin/env python3
"""`surfcert batch --mpi` and the death of a worker rank (bench/results/mpi_fault.md).

1. The heartbeats' cost: the CPU seconds of the ranks themselves (rank 0 and the worker relays,
   not their compute children: the figure the heartbeats could change), sampled from /proc, of
   the same run without and with `mpirun --enable-recovery` (heartbeats on), and, when a second
   executable BEFORE is given (a build without the heartbeats), of that one too. Runs alternate.
2. Detection: under `--enable-recovery --rank-timeout T`, SIGKILL to worker rank 1 once its
   compute child has computed 0.3 s of CPU; the time from the kill to rank 0's message that the
   rank is dead, to the end of mpirun, and whether the output is the single-process batch's
   (apart from time_ms).

The workload: K budget-limited distance lines (two tori 1e-20 apart, budget MS each, always
undecided) each followed by three classify lines. Only the standard library.

usage: mpi_fault_bench.py SURFCERT [--before SURFCERT_BEFORE] [--slow K] [--slow-ms MS]
                          [--repeat R] [--timeout T]
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import tempfile
import threading
import time

MPIRUN = shutil.which("mpirun") or "mpirun"
BASE = [MPIRUN, "--allow-run-as-root", "--oversubscribe"]


def budget_line(i, ms):
    return ('{"id":"slow%d","op":"distance","a":{"type":"torus","center":[0,0,0],'
            '"axis":[0,0,1],"major_radius":3,"minor_radius":1},"b":{"type":"torus","center":'
            '["799999999999999999999/100000000000000000000",0,0],"axis":[0,0,1],'
            '"major_radius":3,"minor_radius":1},"budget_ms":%d}' % (i, ms))


def workload(k, ms):
    out = []
    for i in range(k):
        out.append(budget_line(i, ms))
        for j in range(3):
            out.append('{"id":"%d-%d","op":"classify","a":"x^2+y^2+z^2=1","b":"x^2+y^2=0.%d"}'
                       % (i, j, j + 1))
    return "\n".join(out) + "\n"


def stat(pid):
    """(ppid, own CPU ticks) of a process."""
    with open("/proc/%s/stat" % pid) as f:
        st = f.read().rsplit(")", 1)[1].split()
    return int(st[1]), int(st[11]) + int(st[12])


def rank_of(pid):
    with open("/proc/%s/environ" % pid, "rb") as f:
        env = f.read()
    i = env.find(b"OMPI_COMM_WORLD_RANK=")
    return -1 if i < 0 else int(env[i + 21:env.index(b"\0", i)])


def ranks(parent):
    """{pid: rank} of the MPI processes whose parent is `parent`."""
    out = {}
    for d in os.listdir("/proc"):
        if not d.isdigit():
            continue
        try:
            if stat(d)[0] == parent and rank_of(d) >= 0:
                out[int(d)] = rank_of(d)
        except (OSError, ValueError):
            pass
    return out


def children(parent, what):
    out = []
    for d in os.listdir("/proc"):
        if not d.isdigit():
            continue
        try:
            with open("/proc/%s/cmdline" % d, "rb") as f:
                cmd = f.read()
            if stat(d)[0] == parent and what in cmd:
                out.append(int(d))
        except (OSError, ValueError):
            pass
    return out


def rank_cpu(cmd, inp):
    """CPU seconds of the ranks themselves, sampled every 50 ms until the run ends; wall."""
    tick = os.sysconf("SC_CLK_TCK")
    with open(inp) as f:
        p = subprocess.Popen(cmd, stdin=f, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    seen = {}
    t0 = time.perf_counter()
    while p.poll() is None:
        for pid in ranks(p.pid):
            try:
                seen[pid] = stat(pid)[1] / tick
            except OSError:
                pass
        time.sleep(0.05)
    return sum(seen.values()), time.perf_counter() - t0


def comparable(text):
    """The answers without time_ms; one stopped by its budget by id, status and reason (what it
    had established by then depends on the wall clock, in any two runs)."""
    out = []
    for line in re.sub(r',"time_ms":[0-9.]+', "", text).splitlines():
        if '"reason":"budget"' in line:
            j = json.loads(line)
            line = json.dumps([j.get("id"), j.get("status"), j.get("reason")])
        out.append(line)
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("surfcert")
    ap.add_argument("--before", default="")
    ap.add_argument("--slow", type=int, default=20)
    ap.add_argument("--slow-ms", type=int, default=1000)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--timeout", type=float, default=3)
    a = ap.parse_args()
    print("machine: nproc %d, load average %.2f %.2f %.2f" % (os.cpu_count(), *os.getloadavg()))
    print("date: %s UTC" % time.strftime("%Y-%m-%d %H:%M", time.gmtime()))
    print("mpirun: %s" % subprocess.run([MPIRUN, "--version"], capture_output=True,
                                         text=True).stdout.splitlines()[0])
    tmp = tempfile.mkdtemp()
    inp = os.path.join(tmp, "in.jsonl")
    with open(inp, "w") as f:
        f.write(workload(a.slow, a.slow_ms))
    batch = ["batch", "--mpi", "--threads", "1"]
    variants = [("no recovery", BASE + ["-n", "3", a.surfcert] + batch),
                ("--enable-recovery", BASE + ["--enable-recovery", "-n", "3", a.surfcert] + batch)]
    if a.before:
        variants.insert(0, ("before (no heartbeats)", BASE + ["-n", "3", a.before] + batch))
    print("\n1. CPU seconds of the 3 ranks themselves (not their compute children), %d lines "
          "(%d of %d ms), -n 3 --threads 1; runs alternate:" % (4 * a.slow, a.slow, a.slow_ms))
    got = {name: [] for name, _ in variants}
    for _ in range(a.repeat):
        for name, cmd in variants:
            got[name].append(rank_cpu(cmd, inp))
    for name, cmd in variants:
        cpus = sorted(c for c, _ in got[name])
        print("  %-24s CPU %s s (median %.2f), wall %s s" % (
            name, " ".join("%.2f" % c for c, _ in got[name]), cpus[len(cpus) // 2],
            " ".join("%.1f" % w for _, w in got[name])))
        print("    %s" % " ".join(cmd[len(BASE):]))

    print("\n2. SIGKILL to worker rank 1 under --enable-recovery --rank-timeout %g:" % a.timeout)
    with open(inp) as f:
        single = subprocess.run([a.surfcert, "batch", "--threads", "1"], stdin=f,
                                capture_output=True, text=True)
    for n in (3, 2):
        err = os.path.join(tmp, "err")
        cmd = BASE + ["--enable-recovery", "-n", str(n), a.surfcert] + batch + [
            "--rank-timeout", str(a.timeout)]
        with open(inp) as f, open(err, "w") as e:
            p = subprocess.Popen(cmd, stdin=f, stdout=subprocess.PIPE, stderr=e, text=True)
            victim, t_kill = None, None
            while victim is None and p.poll() is None:
                for pid, r in ranks(p.pid).items():
                    if r == 1 and any(stat(c)[1] >= 30 for c in children(pid, b"--mpi-child")):
                        victim = pid
                time.sleep(0.01)
            os.kill(victim, 9)
            t_kill = time.perf_counter()
            t_seen = None
            out = []
            # rank 0's messages go to err: poll it for the death notice while reading stdout.
            reader = threading.Thread(target=lambda: out.append(p.stdout.read()))
            reader.start()
            while p.poll() is None:
                if t_seen is None and "is silent past" in open(err).read():
                    t_seen = time.perf_counter() - t_kill
                time.sleep(0.01)
            t_end = time.perf_counter() - t_kill
            reader.join()
        text = open(err).read()
        m = re.search(r"retried=(\d+) .*dead_ranks=(\d+) recovery=1 exit=(\d+)", text)
        print("  -n %d: dead found %.1f s after the kill, mpirun ended %.1f s after it (exit %d); "
              "retried=%s dead_ranks=%s exit=%s (single-process batch: %d); output %s" % (
                  n, t_seen if t_seen is not None else float("nan"), t_end, p.returncode,
                  m and m.group(1), m and m.group(2), m and m.group(3), single.returncode,
                  "identical apart from time_ms" if comparable(out[0]) == comparable(single.stdout)
                  else "DIFFERENT"))
        print("    %s" % " ".join(cmd[len(BASE):]))
    print("\nload average after: %.2f %.2f %.2f" % os.getloadavg())
    shutil.rmtree(tmp)


if __name__ == "__main__":
    main()
