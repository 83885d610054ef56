#!/bin/bash
# process_start_bench.sh: what a `surfcert` process costs before it computes anything (issue 12):
# CPU time (task-clock) and page faults (~40 µs each on the development VM) of `--version`,
# an empty `batch --threads 1`, one `distance` CLI query and an empty `batch --threads 2`, for
# each binary given (A/B: the same commands in turn, R runs each; perf stat's mean and spread).
# Figures in bench/results/double_path.md ("Process start").
# Usage: bench/process_start_bench.sh [-r R=20] SURFCERT [SURFCERT...]
set -eu
runs=20
if [ "${1:-}" = "-r" ]; then runs=$2; shift 2; fi
[ $# -ge 1 ] || { echo "usage: $0 [-r R] SURFCERT [SURFCERT...]" >&2; exit 2; }
command -v perf >/dev/null || { echo "needs perf (linux-perf)" >&2; exit 2; }
echo "# process start: $(date -u '+%Y-%m-%d %H:%M UTC'), load average $(cut -d' ' -f1-3 /proc/loadavg)"
echo "Machine: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) cores; perf stat -r $runs -e task-clock,page-faults"
echo
echo "| binary | command | CPU ms (task-clock) | page faults |"
echo "|---|---|---|---|"
one() { # binary, label, command...
  local bin=$1 label=$2; shift 2
  perf stat -x, -e task-clock,page-faults -r "$runs" "$@" 2>&1 >/dev/null </dev/null |
    awk -F, -v b="$bin" -v l="$label" '$3=="task-clock"{t=sprintf("%.2f ± %s", $1, $4)}
      $3=="page-faults"{p=sprintf("%d", $1)} END{printf "| %s | %s | %s | %s |\n", b, l, t, p}'
}
for bin in "$@"; do
  one "$bin" "--version" "$bin" --version
  one "$bin" "batch --threads 1 </dev/null" "$bin" batch --threads 1
  one "$bin" "batch --threads 2 </dev/null" "$bin" batch --threads 2
  one "$bin" "distance (sphere, ellipsoid; 15 digits)" "$bin" distance \
    '(x-3)^2+(y-1/2)^2+z^2=1/16' 'x^2/4+y^2+z^2/9=1'
done
